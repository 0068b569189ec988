#!/usr/bin/python3
"""Baking throughput of btflut against the same work done with scikit-image.

The work, per image of a dataset, after decoding (decode is excluded on both sides): the
grey value (mean of R, G, B) of the masked pixels, their histogram, and the histogram
matching of the reference to it. btflut does it through `btflut bench bake` (which also
fills the bank's grid); scikit-image through numpy and exposure.match_histograms, on one
thread. Rounds are interleaved so machine drift hits both alike; medians are compared.

usage: tools/bench_bake_vs_skimage.py BTFLUT_BINARY DATASET_FOLDER [--rounds N] [--json]
DATASET_FOLDER is a photometric-stereo folder (lights.txt, NAME.K.ext, NAME.mask.ext).
"""
import argparse
import glob
import json
import os
import re
import statistics
import subprocess
import sys
import time

import numpy as np
from PIL import Image
from skimage import exposure


def load_psm(folder):
    files = sorted(glob.glob(os.path.join(folder, "*.*.*")))
    images = [f for f in files if re.search(r"\.\d+\.[A-Za-z]+$", f)]
    images.sort(key=lambda f: int(f.rsplit(".", 2)[1]))
    masks = [f for f in files if ".mask." in f]
    decoded = [np.asarray(Image.open(f).convert("RGB")) for f in images]
    mask = (np.asarray(Image.open(masks[0]).convert("L")) > 0) if masks else np.ones(decoded[0].shape[:2], bool)
    lights = np.loadtxt(os.path.join(folder, "lights.txt"), skiprows=1)
    return decoded, mask, int(np.argmax(lights[:, 2]))


def skimage_bake(images, mask, ref_index):
    ref = images[ref_index].mean(axis=2)[mask]
    luts = []
    for img in images:
        grey = img.mean(axis=2)[mask]
        hist = np.histogram(grey, bins=64, range=(0, 255))[0] / grey.size
        luts.append((hist, exposure.match_histograms(ref, grey)))
    return luts


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("btflut")
    ap.add_argument("dataset")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()

    images, mask, ref_index = load_psm(args.dataset)
    ours_all, ours_one, theirs = [], [], []
    for _ in range(args.rounds):
        out = subprocess.run([args.btflut, "bench", "bake", args.dataset, "--json", "--repeat", "5"],
                             check=True, capture_output=True, text=True).stdout
        result = json.loads(out)
        ours_all.append(result["seconds_median"])
        ours_one.append(result["seconds_median_1_thread"])
        start = time.perf_counter()
        skimage_bake(images, mask, ref_index)
        theirs.append(time.perf_counter() - start)

    t_all, t_one, t_sk = (statistics.median(v) for v in (ours_all, ours_one, theirs))
    report = {
        "dataset": args.dataset,
        "images": len(images),
        "btflut_seconds": t_all,
        "btflut_seconds_1_thread": t_one,
        "skimage_seconds": t_sk,
        "speedup": t_sk / t_all,
        "speedup_1_thread": t_sk / t_one,
    }
    if args.json:
        print(json.dumps(report, indent=1))
    else:
        print(f"bake of {len(images)} images, decode excluded, median of {args.rounds} interleaved rounds")
        print(f"  scikit-image (1 thread):  {t_sk * 1e3:9.2f} ms")
        print(f"  btflut (all cores):       {t_all * 1e3:9.2f} ms   speed-up {t_sk / t_all:6.1f}x (target >= 20x)")
        print(f"  btflut (1 thread):        {t_one * 1e3:9.2f} ms   speed-up {t_sk / t_one:6.1f}x")
    return 0


if __name__ == "__main__":
    sys.exit(main())
