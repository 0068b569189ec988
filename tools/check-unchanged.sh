#!/usr/bin/env bash
# Checks that a change left btflut's outputs byte for byte as they were: bakes of every kind
# (--threads 1), relight, render --native, export folders and the --web page's data (the
# material, its files and the include; not the page's own scripts), made by an old and a new
# binary from the same inputs and compared byte for byte. For refactors that promise
# "behaviour unchanged" (issue 32); prints each output that differs and exits 1 if any does.
#
#   cp build/btflut /tmp/btflut-before        # before the change
#   ... change, rebuild ...
#   bash tools/check-unchanged.sh /tmp/btflut-before build/btflut [DATASET ...]
#
# Datasets default to the bundled material (build/assets/default) and, when present,
# ../shared/data/psm-rock and dome-synth.
set -euo pipefail
old="$(realpath "$1")" new="$(realpath "$2")"
shift 2
cd "$(dirname "$0")/.."
datasets=("$@")
if [ ${#datasets[@]} -eq 0 ]; then
  datasets=(build/assets/default)
  for d in ../shared/data/psm-rock ../shared/data/dome-synth; do [ -d "$d" ] && datasets+=("$d"); done
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# Every kind of bank: the paper's, references blended, regions, colour modes, each light
# model, matched fully and in part, the validated default, the PTM baseline.
kinds=("--references 1" "--references 1 --ptm" "--references 3" "--references 3 --regions 2" "--colour lrgb"
       "--predictor ptm" "--predictor hsh2" "--predictor hsh3 --match 0.5" "--predictor rbf4" "--predictor bln4c"
       "--predictor hsh2 --regions 2" "")
differ=0
made=0
check() {  # NAME: compares $work/old/NAME with $work/new/NAME (files or folders)
  made=$((made + 1))
  # The shader include's text, and the scripts of the three.js recipe an export folder copies,
  # are compared by what they draw (the GL, browser and engine-example tests), not byte for
  # byte: a refactor of shaders/ or src/web/ changes them.
  if ! diff -rq -x 'btflut*.glsl' -x 'btflut.hlsl' -x 'btflut.gdshaderinc' -x 'btflut_material.js' -x 'btflut-three.js' \
    "$work/old/$1" "$work/new/$1" >/dev/null 2>&1; then
    echo "DIFFERS: $1"
    differ=$((differ + 1))
  fi
}
for d in "${datasets[@]}"; do
  name="$(basename "$d")"
  for k in "${!kinds[@]}"; do
    for side in old new; do
      bin="$old"; [ $side = new ] && bin="$new"
      out="$work/$side/$name-$k"
      mkdir -p "$out"
      # shellcheck disable=SC2086
      if ! "$bin" bake "$d" ${kinds[$k]} --threads 1 -q -o "$out/m.btflut" 2>"$out/bake.err"; then
        # A kind this dataset does not allow (lrgb of a grey capture): both must refuse alike.
        [ $side = new ] && echo "refused: $name ${kinds[$k]}: $(cat "$out/bake.err")"
        continue
      fi
      "$bin" relight "$out/m.btflut" --light 35,120 -o "$out/relit.png" -q
      "$bin" relight "$out/m.btflut" --light 62,300 -o "$out/relit-far.png" -q
      "$bin" render "$out/m.btflut" --native --light 35,120 -o "$out/native.png" -q
      "$bin" export "$out/m.btflut" -o "$out/export/" -q
      "$bin" export "$out/m.btflut" --web "$work/page.html" -q
      # The page's data without its scripts ("code") and include, which a refactor of src/web/ or
      # shaders/ may change.
      /usr/bin/python3 - "$work/page.html" "$out/page-data.json" <<'PY'
import json, re, sys
text = open(sys.argv[1]).read()
data = json.loads(re.search(r'<script type="application/json" id="btflut-data">(.*?)</script>', text, re.S).group(1))
data.pop("code")
data.pop("include")
data.pop("bytes")  # counts the include too
for f in [f for f in data["files"] if f.startswith("btflut") and f.endswith(("glsl", "hlsl", "gdshaderinc"))]:
    data["files"].pop(f)
json.dump(data, open(sys.argv[2], "w"), sort_keys=True)
PY
    done
    check "$name-$k"
  done
done
echo "check-unchanged: $made outputs sets compared, $differ differ"
[ "$differ" -eq 0 ]
