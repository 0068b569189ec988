#!/usr/bin/env bash
# The learned bank of views (issue 35, item 5; docs/predictors.md, "Views") on synth's presets
# at btf-9 (9 views x 9 lights, 128 x 128, rectified), every 4th pair held out:
#   - eval across views: the paper's bank (lut), nearest, brdf, the learned model unmatched
#     (neural9), its bank matched at 0, 0.5 and 1 (lut neural9) and bake's validated choice
#     (lut auto: the learned bank at the strength validation picks, or the paper's): PSNR (dB) /
#     histogram L1;
#   - bake on all 81 images: the learned bank against the paper's, time, peak memory and size.
#
#   bash tools/bench-learned-views.sh [BTFLUT]
set -euo pipefail
btflut=${1:-build/btflut}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for preset in concrete foil plastic corduroy; do
  set="$work/$preset"
  "$btflut" synth --preset "$preset" --geometry btf-9 --size 128 --samples 1 -q -o "$set"
  "$btflut" eval "$set" --holdout every:4 --no-gl --modes lut,nearest,brdf,neural9 --predictor references,neural9 \
    --match 0,0.5,1 --json -q -o "$work/out" >/dev/null
  "$btflut" eval "$set" --holdout every:4 --no-gl --modes lut --predictor auto --json -q -o "$work/auto" >/dev/null
  /usr/bin/python3 -c "
import json, sys
j = json.load(open(sys.argv[1]))
names = {'lut K1 R1 grey': 'lut', 'lut neural9 R1 grey match 0': 'lut neural9 m0',
         'lut neural9 R1 grey match 0.5': 'lut neural9 m0.5', 'lut neural9 R1 grey match 1': 'lut neural9 m1'}
modes = j['modes'] + json.load(open(sys.argv[3]))['modes']
print(sys.argv[2] + ': ' + '  '.join(f\"{names.get(m['name'], m['name'])} {m['psnr']:.2f}/{m['l1']:.3f}\" for m in modes))
" "$work/out/eval.json" "$preset" "$work/auto/eval.json"
  for predictor in references neural9; do
    /usr/bin/time -f "%e %M" -o "$work/time" "$btflut" bake "$set" --predictor "$predictor" -o "$work/b.btflut" -q
    read -r seconds kb <"$work/time"
    printf "  bake --predictor %-10s %6s s  %4d MB peak  %6d KB\n" "$predictor" "$seconds" $((kb / 1024)) \
      $(($(stat -c %s "$work/b.btflut") / 1024))
  done
done
