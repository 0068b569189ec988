#!/usr/bin/env bash
# The time `btflut compare` takes on two 1024 x 1024 renders of the default material (two
# light directions): the median of 11 runs of the whole command (start-up, decoding both
# PNGs, every figure), after one warm-up. Target: under 50 ms.
set -euo pipefail
cd "$(dirname "$0")/.."
btflut="${BTFLUT:-build/btflut}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$btflut" bake build/assets/default -o "$work/default.btflut" -q
for light in "-0.5, -0.6, 0.6" "0.6, -0.3, 0.5"; do
  n=$([ -e "$work/a.png" ] && echo b || echo a)
  cat >"$work/$n.json" <<JSON
{"btflut_scene": 1, "image": {"width": 1024, "height": 1024},
 "camera": {"position": [0, -3.2, 2.2], "target": [0, 0, 0], "up": [0, 0, 1], "fov_degrees": 45},
 "light": {"direction": [$light]}, "materials": {"m": "$work/default.btflut"},
 "quads": [{"material": "m", "center": [0, 0, 0], "normal": [0, 0, 1], "tangent": [1, 0, 0], "size": [4, 4], "uv_scale": 2}]}
JSON
  "$btflut" render "$work/$n.json" -o "$work/$n.png" >/dev/null
done
"$btflut" compare "$work/a.png" "$work/b.png" --tolerance psnr=0 >/dev/null
times=()
for _ in $(seq 11); do
  start=$EPOCHREALTIME
  "$btflut" compare "$work/a.png" "$work/b.png" --tolerance psnr=0 >/dev/null
  times+=("$(awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.1f", (b - a) * 1000 }')")
done
median=$(printf '%s\n' "${times[@]}" | sort -n | sed -n 6p)
echo "compare, two 1024x1024 renders of the default material: median $median ms over 11 runs (${times[*]} ms); target 50 ms"
