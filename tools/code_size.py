#!/usr/bin/env python3
"""Reports the source files and functions over issue 48's size limits.

    python3 tools/code_size.py            # lists what is over, exits 0
    python3 tools/code_size.py --check    # exits 1 when anything is over (ctest: btflut_code_size)

Files: src/ and shaders/ sources of more than 600 lines. Functions: a definition at namespace
scope (a line that opens a brace outside any class or function and has a parameter list)
of more than 120 lines, counted from that line to its closing brace. Members defined inside a
class body are not counted (they are short by this codebase's habit). A heuristic, not a parser:
it skips strings' and comments' braces, and is enough for this code's one style
(tools/format.sh).
"""
import re
import sys
from pathlib import Path

MAX_FILE_LINES = 600
MAX_FUNCTION_LINES = 120
ROOT = Path(__file__).resolve().parent.parent
SOURCES = [p for d in ("src", "shaders") for p in sorted((ROOT / d).rglob("*"))
           if p.suffix in (".cpp", ".h", ".glsl", ".js")]


def code_of(line, in_comment):
    """The line without strings, characters and comments; whether a /* */ comment goes on."""
    out, i = [], 0
    while i < len(line):
        if in_comment:
            end = line.find("*/", i)
            if end < 0:
                return "".join(out), True
            i, in_comment = end + 2, False
        elif line.startswith("//", i):
            break
        elif line.startswith("/*", i):
            in_comment, i = True, i + 2
        elif line[i] in "\"'":
            quote, i = line[i], i + 1
            while i < len(line) and line[i] != quote:
                i += 2 if line[i] == "\\" else 1
            i += 1
        else:
            out.append(line[i])
            i += 1
    return "".join(out), in_comment


def long_functions(path):
    """(name, first line, lines) of each namespace-scope definition longer than the limit."""
    lines = path.read_text(errors="replace").splitlines()
    scopes = []  # per open brace: "namespace", "class", "function" or "block"
    found, in_comment, start, name, pending = [], False, 0, "", ""
    for number, raw in enumerate(lines, 1):
        code, in_comment = code_of(raw, in_comment)
        if not code.strip() or code.lstrip().startswith("#"):
            continue
        outside = all(s == "namespace" for s in scopes)
        if outside and "{" not in code and not code.rstrip().endswith(";"):
            pending += " " + code.strip()  # a signature over several lines
        for ch in code:
            if ch == "{":
                head = (pending + " " + code.split("{")[0]).strip()
                if all(s == "namespace" for s in scopes):
                    if re.match(r"^(namespace|extern)\b", head) or not head:
                        kind = "namespace"
                    elif re.match(r"^(template\s*<.*>\s*)?(struct|class|union|enum)\b", head) or "(" not in head:
                        kind = "class"
                    else:
                        kind = "function"
                        match = re.search(r"([\w:~<>]+)\s*\(", head)
                        name, start = (match.group(1) if match else head[:40]), number
                else:
                    kind = "block"
                scopes.append(kind)
                pending = ""
            elif ch == "}" and scopes:
                kind = scopes.pop()
                if kind == "function" and number - start + 1 > MAX_FUNCTION_LINES:
                    found.append((name, start, number - start + 1))
        if outside and code.rstrip().endswith((";", "}")):
            pending = ""
    return found


def main():
    over = 0
    for path in SOURCES:
        relative = path.relative_to(ROOT)
        count = len(path.read_text(errors="replace").splitlines())
        if count > MAX_FILE_LINES:
            print(f"{relative}: {count} lines (over {MAX_FILE_LINES})")
            over += 1
        if path.suffix in (".cpp", ".h"):
            for name, first, length in long_functions(path):
                print(f"{relative}:{first}: {name}, {length} lines (over {MAX_FUNCTION_LINES})")
                over += 1
    print(f"code size: {len(SOURCES)} files read, {over} over the limits")
    return 1 if over and "--check" in sys.argv else 0


if __name__ == "__main__":
    sys.exit(main())
