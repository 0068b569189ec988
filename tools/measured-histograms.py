#!/usr/bin/env python3
# How closely a bank reproduces the histograms of the photographs it was baked from: relights
# BANK at each light of DATASET (lights.txt or a .lp file) and prints the 64-bin grey histogram
# L1 against each photograph over the dataset's mask (issue 34: a measured light is exact).
#
#   python3 tools/measured-histograms.py build/btflut M.btflut ../shared/data/psm-rock
import csv, math, os, subprocess, sys, tempfile

binary, bank, data = sys.argv[1:4]
files = os.listdir(data)
masks = [f for f in files if "mask" in f.lower()]
if os.path.exists(os.path.join(data, "lights.txt")):
    rows = open(os.path.join(data, "lights.txt")).read().split("\n")[1:]
    images = sorted([f for f in files if f.endswith((".tga", ".png")) and "mask" not in f],
                    key=lambda n: int("".join(c for c in n if c.isdigit()) or 0))
    lights = [(name, list(map(float, rows[k].split()))) for k, name in enumerate(images)]
else:
    lp = [f for f in files if f.endswith(".lp")][0]
    lines = [l.split() for l in open(os.path.join(data, lp)).read().split("\n")[1:] if l.strip()]
    lights = [(l[0], list(map(float, l[1:4]))) for l in lines]
work = tempfile.mkdtemp()


def histogram(image):
    command = [binary, "hist", image, "-o", work + "/h.csv", "-q"]
    if masks:
        command += ["--mask", os.path.join(data, masks[0])]
    subprocess.run(command, check=True)
    values = [float(v) for v in list(csv.reader(open(work + "/h.csv")))[1][5:]]
    return [v / sum(values) for v in values]


l1s = []
for name, (x, y, z) in lights:
    norm = math.sqrt(x * x + y * y + z * z)
    light = "%.6f,%.6f" % (math.degrees(math.acos(z / norm)), math.degrees(math.atan2(y, x)) % 360)
    subprocess.run([binary, "relight", bank, "--light", light, "-o", work + "/r.png", "-q"], check=True)
    l1s.append(sum(abs(a - b) for a, b in zip(histogram(work + "/r.png"), histogram(os.path.join(data, name)))))
print("%s: histogram L1 at its %d measured lights: mean %.4f, worst %.4f"
      % (os.path.basename(bank), len(l1s), sum(l1s) / len(l1s), max(l1s)))
