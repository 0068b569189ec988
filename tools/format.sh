#!/usr/bin/env bash
# Formats every C++ file of the repository with clang-format (.clang-format at the root;
# Debian 12's clang-format 14, installed by tools/setup.sh), or, with --check, lists what
# would change and fails (tools/test.sh runs that first, so CI fails on unformatted code).
#
#   bash tools/format.sh            # before a commit
#   bash tools/format.sh --check    # clang-format --dry-run --Werror
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files '*.cpp' '*.h')
if [ "${1:-}" = "--check" ]; then
  if ! clang-format --dry-run --Werror "${files[@]}" 2>/tmp/btflut-format.$$; then
    grep -o '^[^:]*:[0-9]*' /tmp/btflut-format.$$ | sort -u -t: -k1,1 | head -20 >&2
    rm -f /tmp/btflut-format.$$
    echo "format: these files are not formatted: run bash tools/format.sh" >&2
    exit 1
  fi
  rm -f /tmp/btflut-format.$$
  echo "format: ${#files[@]} files formatted"
else
  clang-format -i "${files[@]}"
fi
