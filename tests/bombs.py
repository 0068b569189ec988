#!/usr/bin/env python3
"""Bad and hostile inputs through the btflut command, each bounded in time and memory.

usage: python3 tests/bombs.py BTFLUT_BINARY

Every input of tests/fuzz/regressions/ (the hardening audit's bombs and what fuzzing found)
and a few generated ones (a 200000-deep JSON file, an 8000-node bank) go through each command
that reads that kind of file. Each run must end within 60 s with exit status 1 and one line
on stderr naming the input (the 8000-node bank and the valid-* inputs must work, exit 0),
write no output, and peak
under 300 MB of resident memory (skipped when BTFLUT_SANITIZED=1: sanitizer shadow memory is
not the program's). Prints the worst time and memory seen.
"""
import os
import resource
import struct
import subprocess
import sys
import tempfile
import time
import zlib

btflut = os.path.abspath(sys.argv[1])
here = os.path.dirname(os.path.abspath(__file__))
regressions = os.path.join(here, 'fuzz', 'regressions')
sanitized = os.environ.get('BTFLUT_SANITIZED') == '1'
LIMIT_MB, LIMIT_S = 300, 60


def run(args, cwd, address_space_mb=0):
    """Runs btflut with args (under `ulimit -v` when address_space_mb); returns (exit status,
    stderr text, seconds, peak RSS in MB)."""
    err_path = os.path.join(cwd, 'stderr.txt')

    def limit():
        if address_space_mb:
            size = address_space_mb << 20
            resource.setrlimit(resource.RLIMIT_AS, (size, size))

    with open(err_path, 'wb') as err, open(os.devnull, 'wb') as out:
        start = time.monotonic()
        proc = subprocess.Popen([btflut, *args], cwd=cwd, stdout=out, stderr=err, preexec_fn=limit)
        # wait4 reports this child's own peak memory.
        deadline = start + LIMIT_S
        while True:
            pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                break
            if time.monotonic() > deadline:
                proc.kill()
                pid, status, usage = os.wait4(proc.pid, 0)
                break
            time.sleep(0.01)
        seconds = time.monotonic() - start
    proc.returncode = os.waitstatus_to_exitcode(status)
    return proc.returncode, open(err_path, errors='replace').read(), seconds, usage.ru_maxrss / 1024


def bank_chunk(tag, data):
    return tag + struct.pack('<I', len(data)) + data + struct.pack('<I', zlib.crc32(tag + data) & 0xffffffff)


def spiral_bank(nodes):
    """A valid bank of one layer with `nodes` light directions (entries 2, grid 2)."""
    head = struct.pack('<9I', 2, 1, 2, 1, 0, 4, 4, 1, 8) + struct.pack('<4d', 0, 0, 0, 0) + struct.pack('<I', 1) + b'r'
    layer = struct.pack('<2d', 0, 0) + struct.pack('<I', nodes)
    for n in range(nodes):
        layer += struct.pack('<2d', 80.0 * (n + 0.5) / nodes, (137.50776 * n) % 360) + struct.pack('<I', 0)
    layer += struct.pack(f'<{2 * nodes}f', *([0.0, 1.0] * nodes)) + bytes([2] * 4) + struct.pack('<8H', *([0, 65535] * 4))
    return b'\x89BTFLUT\n' + struct.pack('<I', 1) + bank_chunk(b'HEAD', head) + bank_chunk(b'LAYR', layer) + bank_chunk(b'END ', b'')


def main():
    failures, worst_s, worst_mb, runs = [], 0.0, 0.0, 0
    with tempfile.TemporaryDirectory(prefix='btflut-bombs-') as tmp:
        inputs = {t: [os.path.join(regressions, t, f) for f in sorted(os.listdir(os.path.join(regressions, t)))]
                  for t in os.listdir(regressions)}
        deep = os.path.join(tmp, 'deep.json')
        with open(deep, 'w') as f:
            f.write('{"images": ' + '[' * 200000 + ']' * 200000 + '}')
        inputs.setdefault('manifest', []).append(deep)
        inputs.setdefault('scene', []).append(deep)
        reference = os.path.join(tmp, 'ref.png')  # a small valid image for bake --model
        subprocess.run([btflut, 'synth', '--size', '16', '--correlation-length', '4', '--geometry', 'rti-1', '-q',
                        '-o', os.path.join(tmp, 'ref')], check=True)
        os.rename(os.path.join(tmp, 'ref', 'l1.png'), reference)
        out = os.path.join(tmp, 'out')
        commands = {
            'image': [['match', '{}', '{}', '-o', out + '.png'], ['bake', '--model', os.path.join(tmp, 'p.json'),
                                                                   '--reference', '{}', '-o', out + '.btflut']],
            'bank': [['info', '{}'], ['relight', '{}', '--light', '30,0', '-o', out + '.png'],
                     ['export', '{}', '-o', out + '.png'], ['render', '{}', '--native', '--light', '30,0', '-o', out + '.png']],
            'scene': [['render', '{}', '-o', out + '.png']],
            'manifest': [['bake', '{}', '-o', out + '.btflut'], ['hist', '{}', '-o', out + '.csv']],
            'lp': [['bake', '{}', '-o', out + '.btflut']],
            'params': [['bake', '--model', '{}', '--reference', reference, '-o', out + '.btflut']],
            'histograms': [['plot', '{}', '-o', out + '.png']],
            'names': [['relight', os.path.join(tmp, 'none.btflut'), '--light', '{text}', '-o', out + '.png']],
        }
        with open(os.path.join(tmp, 'p.json'), 'w') as f:
            f.write('{"roughness": 0.4, "nodes": 4, "bins": 32, "lights": [{"theta": 0, "phi": 0}, {"theta": 40, "phi": 0}]}')
        cases = []
        for target, files in inputs.items():
            for path in files:
                if target in ('manifest', 'scene', 'lp') and not path.endswith(('.json', '.lp')):
                    continue
                # Datasets and scenes are recognised by extension: give each its own.
                for template in commands.get(target, []):
                    text = open(path, errors='replace').read() if target == 'names' else ''
                    # valid-* inputs are there so fuzzing reaches deep paths: they must work.
                    expected = 0 if os.path.basename(path).startswith('valid-') else 1
                    cases.append(([a.replace('{text}', text).replace('{}', path) for a in template], path, expected))
        many = os.path.join(tmp, 'many.btflut')
        with open(many, 'wb') as f:
            f.write(spiral_bank(8000))
        cases.append((['info', many], many, 0))

        for args, path, expected in cases:
            status, err, seconds, mb = run(args, tmp)
            runs += 1
            worst_s, worst_mb = max(worst_s, seconds), max(worst_mb, mb)
            problems = []
            if status != expected:
                problems.append(f'exit status {status}, expected {expected}: ' + repr(err[-600:]))
            if expected == 1 and (err.count('\n') != 1 or 'error' not in err):
                problems.append('stderr is not one error line: ' + repr(err[:300]))
            if seconds > LIMIT_S:
                problems.append(f'ran {seconds:.0f} s')
            if not sanitized and mb > LIMIT_MB:
                problems.append(f'peaked at {mb:.0f} MB')
            for leftover in (out + '.png', out + '.btflut', out + '.csv'):
                if os.path.exists(leftover):
                    if expected == 1:
                        problems.append('wrote ' + leftover)
                    os.remove(leftover)
            if problems:
                failures.append(f"btflut {' '.join(args)[:160]}: " + '; '.join(problems))
        # Out of memory (issue 49): under an address-space limit every command that allocates
        # by the input's size ends in one error line and exit 1 (or works), never a signal.
        # Skipped sanitized: the sanitizers reserve terabytes of address space.
        if not sanitized:
            data = os.path.join(tmp, 'synth')
            subprocess.run([btflut, 'synth', '--size', '96', '--geometry', 'rti-24', '-q', '-o', data], check=True)
            bank = os.path.join(tmp, 'synth.btflut')
            subprocess.run([btflut, 'bake', data, '--ptm', '-q', '-o', bank], check=True)
            limited = [(4000, ['synth', '--preset', 'concrete', '--size', size, '-o', os.path.join(tmp, 'big')])
                       for size in ('30000', '60000', '100000')]
            # render: Mesa's llvmpipe crashes in its compiler and rasteriser under ~500 MB, which
            # btflut turns into one line (gl/context.cpp); under ~200 MB no context is made.
            limited += [(mb, ['render', bank, '--native', '--light', '30,40', '-o', out + '.png'])
                        for mb in (200, 300, 500)]
            for mb in (300,):
                limited += [(mb, ['bake', data, '-o', out + '.btflut']),
                            (mb, ['eval', data, '--no-gl', '--modes', 'lut', '-o', os.path.join(tmp, 'eval')]),
                            (mb, ['export', bank, '-o', os.path.join(tmp, 'export') + '/', '--force'])]
            for mb, args in limited:
                status, err, seconds, _ = run(args, tmp, mb)
                runs += 1
                if status not in (0, 1) or (status == 1 and (err.count('\n') != 1 or 'error' not in err)):
                    failures.append(f"ulimit -v {mb} MB: btflut {' '.join(args)[:120]}: exit status {status}: "
                                    + repr(err[-300:]))
                if status == 1 and os.path.exists(out + '.png'):
                    failures.append(f"ulimit -v {mb} MB: btflut {' '.join(args)[:120]}: wrote {out}.png")
                for leftover in (out + '.png', out + '.btflut'):
                    if os.path.exists(leftover):
                        os.remove(leftover)
    print(f'bombs: {runs} runs, worst {worst_s:.2f} s and {worst_mb:.0f} MB peak resident'
          + (' (memory not bounded: sanitized build)' if sanitized else f' (limits {LIMIT_S} s, {LIMIT_MB} MB)'))
    for f in failures:
        print('FAIL', f)
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
