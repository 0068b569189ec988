#!/usr/bin/env python3
"""src/core has no include cycle and every folder keeps to its README.

Each folder of src/core has a README whose "May include:" line names the folders (`bank/`)
its files may include. Every `#include "core/FOLDER/..."` in the folder must name one of those
or the folder itself; the headers beside the folders (result.h, check.h, parallel.h,
random.h) serve every part. And the folders' order in src/core/README.md's table is the
layering: a folder may include only folders above it."""
import pathlib
import re
import sys

core = pathlib.Path(__file__).resolve().parent.parent / "src" / "core"
table = re.findall(r"^\| `([a-z_]+)/` \|", (core / "README.md").read_text(), re.M)
problems = []
folders = sorted(p.name for p in core.iterdir() if p.is_dir())
for name in folders:
    if name not in table:
        problems.append(f"src/core/README.md: folder {name}/ is not in the table")
for name in folders:
    readme = core / name / "README.md"
    if not readme.exists():
        problems.append(f"src/core/{name}/: no README.md")
        continue
    text = readme.read_text()
    match = re.search(r"May include:(.*?)(?:\n\n|\Z)", text, re.S)
    if not match:
        problems.append(f"src/core/{name}/README.md: no 'May include:' line")
        continue
    allowed = set(re.findall(r"`([a-z_]+/)`", match.group(1)))
    above = set(table[: table.index(name)]) if name in table else set()
    for source in sorted((core / name).glob("*.[ch]*")):
        for number, line in enumerate(source.read_text().splitlines(), 1):
            inc = re.match(r'\s*#include "core/([^"]+)"', line)
            if not inc:
                continue
            path = inc.group(1)
            if "/" not in path:
                continue  # result.h, check.h, parallel.h, random.h: every part's
            part = path.split("/")[0] + "/"
            if part == name + "/":
                continue
            where = f"src/core/{name}/{source.name}:{number}"
            if part not in allowed:
                problems.append(f"{where}: includes core/{path}, which {name}/README.md does not allow")
            if part[:-1] not in above:
                problems.append(f"{where}: includes core/{path}, a folder below {name}/ in src/core/README.md")
for p in problems:
    print(p)
print(f"core layers: {len(problems)} problem(s)" if problems else f"core layers: {len(folders)} folders, no include goes down")
sys.exit(1 if problems else 0)
