#!/usr/bin/env bash
# The three.js recipe (examples/three/, docs/engines.md) in headless Chromium: the page's
# screenshot of an export against `btflut relight --grid` at the same light, for one
# reference, a light model and blended references (and, with the shared capture, RGB banks).
#
#   bash tests/three_check.sh BTFLUT DEFAULT_MATERIAL [SHARED_DATA]
set -euo pipefail
btflut=$1 default=$2 data=${BTFLUT_DATA:-${3:-}}
repo="$(cd "$(dirname "$0")/.." && pwd)"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
light=30,40
# name | bake options | tolerance (as the engine example's: docs/engines.md, "Accuracy")
banks=("one|$default --references 1|max=2" "hsh2|$default --predictor hsh2|p99=2,mean=0.2"
       "references|$default --references 3|max=2")
if [ ! -d "$data/psm-rock" ] && [ "${BTFLUT_REQUIRE_DATA:-0}" = 1 ]; then
  echo "three_check: $data/psm-rock is missing (set BTFLUT_DATA)" >&2
  exit 1
fi
if [ -d "$data/psm-rock" ]; then
  banks+=("rock-rgb|$data/psm-rock --colour rgb|max=2" "rock-ptm-albedo|$data/psm-rock --predictor ptm|p99=2,mean=0.2"
          "rock-lrgb|$data/psm-rock --references 4 --colour lrgb|max=2")
fi
for entry in "${banks[@]}"; do
  IFS='|' read -r name bake tolerance <<<"$entry"
  # shellcheck disable=SC2086
  "$btflut" bake $bake -o "$work/$name.btflut" -q
  "$btflut" export "$work/$name.btflut" -o "$work/$name" >/dev/null
  "$btflut" relight "$work/$name.btflut" --grid --light "$light" -o "$work/$name-grid.png" -q
  read -r width height channels < <(/usr/bin/python3 -c "import json,sys; r=json.load(open(sys.argv[1]))['reference']; print(r['width'], r['height'], r['channels'])" "$work/$name/material.json")
  bash "$repo/tools/browser-shot.sh" "file://$repo/examples/three/relight.html#material=file://$work/$name/&light=$light" \
    "$width" "$height" "$work/$name-shot.png"
  # The material at the top left, in the reference's channels (a grey one is drawn R = G = B).
  /usr/bin/python3 - "$work/$name-shot.png" "$width" "$height" "$channels" "$work/$name-three.png" <<'PY'
import sys
from PIL import Image
shot, w, h, channels, out = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
image = Image.open(shot).convert("RGB").crop((0, 0, w, h))
if channels == 1:
    r, g, b = image.split()
    assert r.tobytes() == g.tobytes() == b.tobytes(), "a grey material drawn with colour"
    image = r
image.save(out)
PY
  if ! figures=$("$btflut" compare "$work/$name-three.png" "$work/$name-grid.png" --tolerance "$tolerance"); then
    echo "three.js, $name at $light: $figures" >&2
    exit 1
  fi
  echo "three.js, $name at $light: $figures"
done
