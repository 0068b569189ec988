#!/usr/bin/env python3
"""The README's and docs/predictors.md's account of the default bank against the bank itself.

Bakes the bundled material as `bash tools/run-default.sh` does (the default, --predictor auto),
reads `btflut info --json`, and checks every figure the two documents state about it: the
predictor, its multiply-adds, the measured lights, the match strength between them, and the
validation L1 and PSNR of the choice and of the paper's bank. A change of kind, target or
validation that moves them fails here until the documents say what the bank now is.

    python3 tests/readme_figures.py BTFLUT DEFAULT_MATERIAL
"""
import json
import os
import re
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
btflut, material = sys.argv[1], sys.argv[2]
failures = []


def bank_facts():
    with tempfile.TemporaryDirectory() as work:
        bank = os.path.join(work, "default.btflut")
        subprocess.run([btflut, "bake", material, "-o", bank, "-q"], check=True)
        info = json.loads(subprocess.run([btflut, "info", bank, "--json"], check=True, capture_output=True,
                                         text=True).stdout)
    selection = info["selection"]
    chosen = selection["chosen"]
    candidates = {c["name"]: c for c in selection["candidates"]}

    def validation(name, match):
        for v in candidates[name]["validation"]:
            if abs(v["match"] - match) < 1e-9:
                return v
        raise KeyError(f"{name} has no validation at match {match}")

    ours, paper = validation(chosen["name"], chosen["match"]), validation("K1", 1.0)
    return {
        "predictor": chosen["name"],
        "multiply-adds": str(info["blend"]["multiply_adds_per_texel"]),
        "measured lights": str(info["layers"][0]["light_nodes"]),
        "match": f"{chosen['match']:.2f}",
        "L1": f"{ours['l1']:.3f}",
        "paper's L1": f"{paper['l1']:.3f}",
        "PSNR": f"{ours['psnr']:.1f}",
        "paper's PSNR": f"{paper['psnr']:.1f}",
    }


def check(document, patterns, facts):
    text = " ".join(open(os.path.join(here, "..", document), encoding="utf-8").read().split())
    for fact, pattern in patterns.items():
        found = re.search(pattern, text)
        if not found:
            failures.append(f"{document}: no statement of the default bank's {fact} (looked for /{pattern}/)")
        elif found.group(1) != facts[fact]:
            failures.append(f"{document}: says the default bank's {fact} is {found.group(1)}; "
                            f"`btflut info --json` says {facts[fact]}")


facts = bank_facts()
check("README.md", {
    "predictor": r"For the bundled material that is `(\w+)`",
    "multiply-adds": r"decodes in (\d+) multiply-adds a texel",
    "measured lights": r"matched fully at the (\d+) measured lights",
    "match": r"and ([0-9.]+) of the way between them",
    "L1": r"64-bin L1 ([0-9.]+) against [0-9.]+\)",
    "paper's L1": r"64-bin L1 [0-9.]+ against ([0-9.]+)\)",
    "PSNR": r"at ([0-9.]+) dB against [0-9.]+\.",
    "paper's PSNR": r"at [0-9.]+ dB against ([0-9.]+)\.",
}, facts)
check("docs/predictors.md", {
    "predictor": r"On the bundled material auto chooses `(\w+)`",
    "match": r"On the bundled material auto chooses `\w+` at match ([0-9.]+)",
    "L1": r"validation L1 ([0-9.]+) against the one-reference bank's [0-9.]+",
    "paper's L1": r"validation L1 [0-9.]+ against the one-reference bank's ([0-9.]+)",
    "PSNR": r"PSNR ([0-9.]+) dB against [0-9.]+ dB",
    "paper's PSNR": r"PSNR [0-9.]+ dB against ([0-9.]+) dB",
}, facts)
for line in failures:
    print("readme_figures: " + line, file=sys.stderr)
if failures:
    sys.exit(1)
print("readme_figures: README.md and docs/predictors.md describe the default bank as info prints it: " +
      ", ".join(f"{k} {v}" for k, v in facts.items()))
