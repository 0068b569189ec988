#!/usr/bin/env python3
"""Writes the hand-made bad inputs of the hardening audit (issue 10) into regressions/TARGET/.

Run once; the files are committed. Inputs that fuzzing finds are added there as they are
(libFuzzer's crash-* files, renamed to say what they do). The regression test
(tests/test_fuzz_regressions.cpp) runs every file through its parser; tests/bombs.py runs
the bomb inputs through the btflut command and bounds each run's time and memory.
"""
import os
import struct
import zlib

here = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'regressions')


def put(target, name, data):
    os.makedirs(os.path.join(here, target), exist_ok=True)
    with open(os.path.join(here, target, name), 'wb') as f:
        f.write(data if isinstance(data, bytes) else data.encode())


# --- images ---------------------------------------------------------------------------
def png_chunk(tag, data):
    return struct.pack('>I', len(data)) + tag + data + struct.pack('>I', zlib.crc32(tag + data) & 0xffffffff)


def png(width, height, colour=0, depth=8, idat=zlib.compress(b'\0' * 8)):
    return (b'\x89PNG\r\n\x1a\n' + png_chunk(b'IHDR', struct.pack('>IIBBBBB', width, height, depth, colour, 0, 0, 0))
            + png_chunk(b'IDAT', idat) + png_chunk(b'IEND', b''))


put('image', 'png-claims-20000x20000.png', png(20000, 20000))
put('image', 'png-claims-16000x16000-rgb16-without-data.png', png(16000, 16000, 2, 16))
tga = lambda kind, w, h, bits=24: bytes([0, 0, kind]) + bytes(5) + struct.pack('<HHHH', 0, 0, w, h) + bytes([bits, 0])
put('image', 'tga-claims-65535x65535.tga', tga(2, 65535, 65535) + bytes(16))
put('image', 'tga-rle-8000x8000-data-missing.tga', tga(10, 8000, 8000) + bytes([0x81, 10, 20, 30]))
put('image', 'tga-rle-colour-mapped-data-missing.tga',
    bytes([0, 1, 9, 0, 0, 2, 0, 24]) + struct.pack('<HHHH', 0, 0, 4000, 4000) + bytes([8, 0]) + bytes(6) + bytes([0x85, 1]))


def jpeg(width, height, progressive=False, tables=True, dht_counts=None):
    soi = b'\xff\xd8'
    dqt = b'\xff\xdb' + struct.pack('>HB', 67, 0) + bytes([1] * 64) if tables else b''
    counts = dht_counts or [0, 1, 5, 1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0]
    symbols = bytes(range(min(sum(counts), 256))) + bytes(max(0, sum(counts) - 256))
    dht = b'\xff\xc4' + struct.pack('>HB', 3 + 16 + len(symbols), 0) + bytes(counts) + symbols if tables else b''
    sof = (b'\xff\xc2' if progressive else b'\xff\xc0') + struct.pack('>HBHHB', 11, 8, height, width, 1) + bytes([1, 0x11, 0])
    sos = b'\xff\xda' + struct.pack('>HB', 8, 1) + bytes([1, 0]) + bytes([0, 63 if not progressive else 0, 0])
    return soi + dqt + dht + sof + sos + b'\x12\x34' * 8 + b'\xff\xd9'


put('image', 'jpeg-claims-60000x60000.jpg', jpeg(60000, 60000, tables=False))
put('image', 'jpeg-progressive-claims-15000x15000.jpg', jpeg(15000, 15000, progressive=True))
# stb_image's stbi__build_huffman writes past its table for a DHT with more than 256 codes.
put('image', 'jpeg-dht-with-300-codes.jpg', jpeg(16, 16, dht_counts=[0, 0, 0, 0, 0, 0, 0, 0, 50, 50, 50, 50, 50, 50, 0, 0]))
bmp = b'BM' + struct.pack('<IHHI', 0, 0, 0, 54) + struct.pack('<IiiHHIIiiII', 40, 1 << 24 | 1, 20000, 1, 24, 0, 0, 0, 0, 0, 0)
put('image', 'bmp-claims-16777217x20000.bmp', bmp + bytes(16))


# --- banks ----------------------------------------------------------------------------
def bank_chunk(tag, data):
    return tag + struct.pack('<I', len(data)) + data + struct.pack('<I', zlib.crc32(tag + data) & 0xffffffff)


def bank(ref_w, ref_h, extra_chunks=b'', embedded=0, entries=2, grid=2, nodes=1):
    head = struct.pack('<9I', entries, 1, grid, 1, embedded, ref_w, ref_h, 1, 8) + struct.pack('<4d', 0, 0, 0, 0)
    head += struct.pack('<I', 1) + b'r'
    layer = struct.pack('<2d', 0, 0) + struct.pack('<I', nodes)
    for n in range(nodes):
        layer += struct.pack('<2d', 80.0 * n / max(nodes, 1), 137.5 * n) + struct.pack('<I', 0)
    layer += struct.pack(f'<{nodes * entries}f', *([0.0, 1.0] * nodes)) + bytes(grid * grid)
    layer += struct.pack(f'<{grid * grid * entries}H', *([0, 65535] * grid * grid))
    return (b'\x89BTFLUT\n' + struct.pack('<I', 1) + bank_chunk(b'HEAD', head) + bank_chunk(b'LAYR', layer)
            + extra_chunks + bank_chunk(b'END ', b''))


ptm_header = lambda w, h: struct.pack('<II', w, h) + struct.pack('<6f', *[1.0] * 6) + struct.pack('<6f', *[0.0] * 6)
put('bank', 'ptm-claims-60000x60000-reference-16x16.btflut', bank(16, 16, bank_chunk(b'PTMC', ptm_header(60000, 60000))))
put('bank', 'reference-and-ptm-claim-60000x60000.btflut', bank(60000, 60000, bank_chunk(b'PTMC', ptm_header(60000, 60000))))
put('bank', 'ptm-plane-claims-16000x16000.btflut',
    bank(16, 16, bank_chunk(b'PTMC', ptm_header(16, 16) + struct.pack('<I', 60) + png(16000, 16000, 2)[:60])))
put('bank', 'embedded-reference-claims-16000x16000.btflut',
    bank(16, 16, bank_chunk(b'REFI', png(16000, 16000)), embedded=1))
put('bank', 'one-layer-one-node.btflut', bank(4, 4))  # cannot follow the light

# --- text files -------------------------------------------------------------------------
put('manifest', 'theta-1e999.json', '{"images": [{"file": "a.png", "light": {"theta": 1e999, "phi": 0}}]}')
put('manifest', 'nested-2000-deep.json', '{"images": ' + '[' * 2000 + ']' * 2000 + '}')
put('manifest', 'mask-number.json', '{"mask": 5, "images": [{"file": "a.png", "light": {"theta": 1, "phi": 0}}]}')
put('scene', 'mode-5.json', '{"light": {"direction": [0,0,1]}, "materials": {"a": "a.btflut"}, "quads": '
    '[{"material": "a", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0], "mode": 5}]}')
put('scene', 'width-4294967360.json', '{"image": {"width": 4294967360, "height": 64}, "light": {"direction": [0,0,1]}, '
    '"materials": {"a": "a.btflut"}, "quads": [{"material": "a", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0]}]}')
put('scene', 'light-1e308.json', '{"light": {"direction": [1e308, 1e308, 0]}, "materials": {"a": "a.btflut"}, "quads": '
    '[{"material": "a", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0]}]}')
put('scene', 'theta-1e999.json', '{"light": {"direction": [0, 1e999, 1]}, "materials": {"a": "a.btflut"}, "quads": []}')
put('params', 'types.json', '{"roughness": 0.4, "brdf": 5, "method": [], "samples": 1e300, "seed": -1}')
put('params', 'samples-1e300.json', '{"roughness": 0.4, "samples": 1e300}')
put('lp', 'count-overflow.lp', '99999999999999999999\na.png 0 0 1\n')
put('lp', 'component-1e999.lp', '1\na.png 1e999 0 1\n')
put('lights', 'subnormal.txt', '1\n1e-320 0 1\n')
put('histograms', 'bin-1e999.csv', 'name,theta_i,phi_i,theta_r,phi_r,b0,b1\na,0,0,0,0,1e999,0\n')
put('names', 'bonn-999.txt', 'tl999 pl999 tv999 pv999.jpg')
