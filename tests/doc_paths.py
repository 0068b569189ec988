#!/usr/bin/env python3
"""Every repository path that the docs, the README and source comments name exists.

A path is a token that starts with one of the top-level folders and ends in a file
extension (src/core/bank/lut_bank.h, tests/test_lut.cpp, docs/eval.md) or names a folder
with a trailing slash (src/core/bank/). Placeholders in capitals (shaders/NAME) and files
that tests create (shaders/broken.frag) are not paths of the repository."""
import pathlib
import re
import subprocess
import sys

root = pathlib.Path(__file__).resolve().parent.parent
files = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard"], cwd=root,
                       capture_output=True, text=True, check=True).stdout.split()
texts = [f for f in files if re.search(r"\.(md|h|cpp|glsl|frag|vert|py|sh|txt)$", f) and not f.startswith("tests/fuzz/regressions/")]
pattern = re.compile(r"\b((?:src|tests|tools|shaders|docs|examples|bench|assets)/[A-Za-z0-9_./-]*[A-Za-z0-9_/])")
# Files that tests, or the commands the docs give, create.
created_by_tests = {"shaders/broken.frag", "examples/scene/default.btflut"}
missing = []
for name in texts:
    for number, line in enumerate((root / name).read_text(errors="replace").splitlines(), 1):
        for path in pattern.findall(line):
            if re.search(r"[A-Z]{3,}", path) or path in created_by_tests:
                continue  # a placeholder (NAME, TARGET)
            if not (path.endswith("/") or re.search(r"\.[a-z]+$", path)):
                continue  # a word, not a file or folder name
            if path.startswith("assets/default") or path.startswith("tests/btflut_tests"):
                continue  # made by the build
            if not (root / path).exists():
                missing.append(f"{name}:{number}: {path}")
# The glossary's list of kinds is the enum's (src/core/predict/predictor.h, PredictorKind).
header = (root / "src/core/predict/predictor.h").read_text()
enum = re.search(r"enum class PredictorKind[^{]*\{([^}]*)\}", header)
kinds = [k.lower() for k in re.findall(r"^\s*(\w+)\s*=", enum.group(1), re.M)] if enum else []
listed = re.search(r"The kinds:\s*([a-z, \n]+)\.", (root / "src/core/README.md").read_text())
listed = [k.strip() for k in listed.group(1).replace("\n", " ").split(",")] if listed else []
if not kinds or kinds != listed:
    missing.append(f"src/core/README.md: its kinds {listed} are not PredictorKind's {kinds}")
for m in missing:
    print(m)
print(f"doc paths: {len(missing)} missing" if missing else "doc paths: every named file exists")
sys.exit(1 if missing else 0)
