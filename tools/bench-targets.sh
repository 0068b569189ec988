#!/usr/bin/env bash
# Issue 34's measurements, side by side: two btflut builds (before and after a change to how
# banks estimate their targets between measured lights) on the bundled material, the shared
# data and a rendered concrete. Prints, per dataset and build, eval's lut auto, lut hsh2 and
# the paper's bank (held-out L1, PSNR and the target's own L1); across views (synth btf-25,
# the new build) the paper's bank with the validated target and with the blend; then the
# default bake's time (validation included; the two builds alternating, best of two) and
# their ratio.
#
#   bash tools/bench-targets.sh OLD/btflut NEW/btflut     # e.g. a worktree of main, build/btflut
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -eq 2 ] || { echo "usage: tools/bench-targets.sh OLD_BTFLUT NEW_BTFLUT" >&2; exit 2; }
old=$1 new=$2
data="${BTFLUT_DATA:-../shared/data}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$new" synth --preset concrete --geometry rti-49 -q -o "$work/concrete"
"$new" synth --preset concrete --geometry btf-25 --size 64 --correlation-length 6 -q -o "$work/btf"

for spec in "build/assets/default every:4" "$data/dome-synth every:4" "$work/concrete every:4" "$data/psm-rock loo" "$data/psm-rock every:4"; do
  set -- $spec
  for build in old new; do
    "${!build}" eval "$1" --holdout "$2" --no-gl --modes lut --predictor auto,hsh2,references --json -o "$work/eval" \
      >"$work/eval.json" 2>/dev/null
    /usr/bin/python3 - "$work/eval.json" "$(basename "$1") $2 $build" <<'PY'
import json, sys
report = json.load(open(sys.argv[1]))
for m in report['modes']:
    target = m.get('target_l1')
    print(f"{sys.argv[2]:28} {m['name']:22} L1 {m['l1']:.4f}  PSNR {m['psnr']:.2f}  target "
          + (f"{target:.4f}" if target is not None else "-"))
PY
  done
done

"$new" eval "$work/btf" --no-gl --target measured,blend --json -o "$work/eval" >"$work/eval.json" 2>/dev/null
/usr/bin/python3 - "$work/eval.json" "btf-25 across views" <<'PY'
import json, sys
for m in json.load(open(sys.argv[1]))['modes']:
    print(f"{sys.argv[2]:28} {m['name']:22} L1 {m['l1']:.4f}  PSNR {m['psnr']:.2f}")
PY

for dataset in build/assets/default "$data/dome-synth" "$data/psm-rock" "$work/concrete"; do
  declare -A best=()
  for _ in 1 2; do
    for build in old new; do
      start=$EPOCHREALTIME
      "${!build}" bake "$dataset" -o "$work/$build.btflut" -q --threads 2
      t=$(awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.2f", b - a }')
      if [ -z "${best[$build]:-}" ] || awk -v t="$t" -v b="${best[$build]}" 'BEGIN { exit !(t < b) }'; then
        best[$build]=$t
      fi
    done
  done
  echo "bake $(basename "$dataset"): before ${best[old]} s, now ${best[new]} s, ratio" \
    "$(awk -v a="${best[old]}" -v b="${best[new]}" 'BEGIN { printf "%.2f", b / a }') (target <= 1.5)"
  unset best
done
