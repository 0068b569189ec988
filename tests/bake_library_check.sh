#!/usr/bin/env bash
# tools/bake-library.sh on a small library: three synthetic materials and one broken one,
# baked two at a time with GNU parallel; then the Slurm array script's tasks run by hand
# (as Slurm would, by SLURM_ARRAY_TASK_ID) and its summary step.
set -euo pipefail
btflut="$1"
repo="$(cd "$(dirname "$0")/.." && pwd)"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
mkdir lib
for m in concrete foil plastic; do
  "$btflut" synth --preset "$m" --geometry rti-8 --size 32 --samples 1 --correlation-length 4 -q -o "lib/$m"
done
mkdir lib/broken
echo '{"btflut_dataset": 1, "images": [{"file": "gone.png", "light": {"theta": 10, "phi": 0}}]}' >lib/broken/btflut-dataset.json

if BTFLUT="$btflut" bash "$repo/tools/bake-library.sh" lib out --jobs 2 >log.txt; then
  echo "a failed material must make the exit status 1"; exit 1
fi
grep -q "3 baked, 1 failed" out/summary.md
grep -q "| broken | failed | .*gone.png: cannot open" out/summary.md
for m in concrete foil plastic; do
  grep -q "| $m | ok |" out/summary.md
  "$btflut" info "out/$m.btflut" >/dev/null
done

for task in 0 1 2 3; do
  SLURM_ARRAY_TASK_ID=$task SLURM_SUBMIT_DIR="$repo" BTFLUT="$btflut" SLURM_CPUS_PER_TASK=1 \
    bash "$repo/tools/bake-library.slurm" lib slurm-out || true
done
if bash "$repo/tools/bake-library.sh" --summary slurm-out >/dev/null; then exit 1; fi
grep -q "3 baked, 1 failed" slurm-out/summary.md
echo "bake-library: 3 baked, 1 failed and said so, with GNU parallel and as Slurm array tasks"
