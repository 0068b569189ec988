#!/usr/bin/python3
"""Agreement of `btflut match` with scikit-image's exposure.match_histograms on 8-bit images.

Both map each source grey level through c_target^-1(c_source(level)); btflut treats each
level as a cell of width one (the middle of its quantile range, see src/core/histogram/lut.h) where
scikit-image takes the top of its step, and keeps empty stretches of the target empty where
scikit-image interpolates across them. The gate: mean absolute difference <= 0.5 grey levels
for every pair. btflut runs undithered (--no-dither) and writes 16 bits, so the comparison
is of the mappings themselves.

usage: tools/compare_skimage.py BTFLUT_BINARY [DATA_FOLDER ...]
Pairs come from the images of each DATA_FOLDER (grey = mean of R, G, B rounded to 8 bits)
plus synthetic smooth images. Exit status 1 when a pair exceeds the gate.
"""
import glob
import os
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image
from skimage import exposure

GATE = 0.5


def grey8(path):
    a = np.asarray(Image.open(path).convert("RGB"), dtype=np.float64)
    return np.clip(np.rint(a.mean(axis=2)), 0, 255).astype(np.uint8)


def synthetic(seed, shape=(240, 320)):
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0:shape[0], 0:shape[1]]
    base = 0.5 + 0.3 * np.sin(x * rng.uniform(0.01, 0.08) + seed) * np.cos(y * rng.uniform(0.01, 0.08))
    base += rng.normal(0, rng.uniform(0.02, 0.15), shape)
    gamma = rng.uniform(0.5, 2.0)
    return np.clip(np.rint(255 * np.clip(base, 0, 1) ** gamma), 0, 255).astype(np.uint8)


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 2
    btflut = sys.argv[1]
    images = []
    for folder in sys.argv[2:]:
        files = sorted(f for f in glob.glob(os.path.join(folder, "*"))
                       if f.lower().endswith((".png", ".tga", ".jpg", ".bmp")) and "mask" not in f)
        images += [(os.path.basename(f), grey8(f)) for f in files[:6]]
    images += [(f"synthetic{s}", synthetic(s)) for s in range(6)]

    worst = 0.0
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for i, (src_name, src) in enumerate(images):
            for j, (tpl_name, tpl) in enumerate(images):
                if i == j or (j - i) % len(images) not in (1, 3) or src.shape != tpl.shape:
                    continue
                sp, tp, op = (os.path.join(tmp, n) for n in ("s.png", "t.png", "o.png"))
                Image.fromarray(src).save(sp)
                Image.fromarray(tpl).save(tp)
                subprocess.run([btflut, "match", sp, tp, "-o", op, "--depth", "16", "--no-dither"],
                               check=True, stdout=subprocess.DEVNULL)
                ours = np.asarray(Image.open(op), dtype=np.float64) / 65535.0 * 255.0
                theirs = exposure.match_histograms(src, tpl).astype(np.float64)
                diff = float(np.mean(np.abs(ours - theirs)))
                worst = max(worst, diff)
                rows.append((src_name, tpl_name, diff, float(np.max(np.abs(ours - theirs)))))
    print(f"{'source':>22} {'template':>22} {'mean |diff|':>12} {'max |diff|':>11}  (grey levels)")
    for s, t, d, m in rows:
        print(f"{s:>22} {t:>22} {d:12.3f} {m:11.3f}")
    print(f"pairs: {len(rows)}, worst mean |diff|: {worst:.3f} grey levels (gate {GATE})")
    ok = worst <= GATE
    print("compare_skimage: " + ("PASS" if ok else "FAIL"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
