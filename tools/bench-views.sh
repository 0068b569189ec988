#!/usr/bin/env bash
# The view half of eval (docs/eval.md, "Several views") on synth's presets: each material
# rendered at curet-c2 (11 light-view pairs, leave-one-out) and btf-9 (9 views x 9 lights,
# 128 x 128, every 4th pair held out), then eval with the banks in the layers and isotropic
# domains (curet-c2: bake's choice, isotropic, as it has one light per view). Prints the held-out histogram L1 per mode, and eval's time.
#
#   bash tools/bench-views.sh [BTFLUT]
set -euo pipefail
btflut=${1:-build/btflut}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf "%-9s %-9s %6s  %s\n" preset geometry "eval s" "held-out histogram L1 per mode (domain)"
for preset in concrete foil plastic corduroy; do
  for geometry in curet-c2 btf-9; do
    "$btflut" synth --preset "$preset" --geometry "$geometry" --size 128 --samples 1 -q -o "$work/$preset-$geometry"
    holdout=every:4 domains=layers,isotropic
    # curet-c2: one light per view, so a bank over view layers cannot follow the light.
    [ "$geometry" = curet-c2 ] && holdout=loo domains=auto
    start=$(date +%s%N)
    "$btflut" eval "$work/$preset-$geometry" --holdout "$holdout" --domain "$domains" --json -q -o "$work/out" >/dev/null
    ms=$(( ($(date +%s%N) - start) / 1000000 ))
    summary=$(/usr/bin/python3 -c "
import json, sys
j = json.load(open(sys.argv[1]))
print('  '.join(f\"{m['name'].replace('lut K1 R1 grey', 'lut')} ({m['domain']}) {m['l1']:.3f}\" for m in j['modes']))" "$work/out/eval.json")
    printf "%-9s %-9s %6s  %s\n" "$preset" "$geometry" "$((ms / 1000)).$((ms % 1000 / 100))" "$summary"
  done
done
