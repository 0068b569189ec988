#!/usr/bin/env bash
# btflut in a real browser (headless Chromium, WebGL2 on SwiftShader), against
# `btflut relight --grid` at the same light, for one reference, a light model, blended
# references and a learned model (and, with the shared capture, RGB banks):
#  - the page `export --web` writes, opened at #light=30,40&zoom=1&ui=0 and cropped to the
#    material; it is at most 1.4 times the engine export's files; its 2D view with the panel and
#    its sphere draw with no console message; without WebGL2 it says so;
#  - the three.js recipe (examples/three/, docs/engines.md) on the engine export: the
#    repository's page with Debian's three.js (r111, a classic script), and the page the export
#    writes into its folder (three.html) with npm's current one (0.187, an ES module: fetched
#    once into ~/.cache/btflut/npm, or $BTFLUT_THREE_MODULE's three.module.js).
#
#   bash tests/browser_check.sh BTFLUT DEFAULT_MATERIAL [SHARED_DATA]
set -euo pipefail
btflut=$1 default=$2 data=${BTFLUT_DATA:-${3:-}}
repo="$(cd "$(dirname "$0")/.." && pwd)"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
light=30,40
# name | bake options | tolerance (as the engine example's: docs/engines.md, "Accuracy") | relight's
# view (the pages draw the quad seen from the front)
"$btflut" synth --preset concrete --geometry btf-3 --size 32 --correlation-length 4 --samples 1 -q -o "$work/btf"
banks=("one|$default --references 1|max=2" "hsh2|$default --predictor hsh2|p99=2,mean=0.2"
       "references|$default --references 3|max=2" "neural5|$default --predictor neural5 --budget 5s|p99=2,mean=0.2"
       "views|$work/btf --predictor neural4|p99=2,mean=0.2|--view 0,0")
if [ ! -d "$data/psm-rock" ] && [ "${BTFLUT_REQUIRE_DATA:-0}" = 1 ]; then
  echo "browser_check: $data/psm-rock is missing (set BTFLUT_DATA)" >&2
  exit 1
fi
if [ -d "$data/psm-rock" ]; then
  banks+=("rock-rgb|$data/psm-rock --colour rgb|max=2" "rock-ptm-albedo|$data/psm-rock --predictor ptm|p99=2,mean=0.2"
          "rock-lrgb-regions|$data/psm-rock --references 4 --colour lrgb --regions 2|max=2")
fi

# Current three.js, as an ES module.
three_version=0.187.0
three_module=${BTFLUT_THREE_MODULE:-${XDG_CACHE_HOME:-$HOME/.cache}/btflut/npm/three-$three_version/node_modules/three/build/three.module.js}
if [ ! -f "$three_module" ]; then
  command -v npm >/dev/null || { echo "browser_check: npm not found (bash tools/setup.sh installs it)" >&2; exit 1; }
  prefix=${three_module%/node_modules/three/build/three.module.js}
  mkdir -p "$prefix"
  if ! npm install --no-save --no-audit --no-fund --prefix "$prefix" "three@$three_version" >"$work/npm.log" 2>&1; then
    cat "$work/npm.log" >&2
    echo "browser_check: npm could not fetch three@$three_version (npm's registry must be reachable)" >&2
    exit 1
  fi
fi

# The shot's top-left WIDTH x HEIGHT in the material's channels (a grey one is drawn R = G = B).
crop() {
  /usr/bin/python3 - "$@" <<'PY'
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
}
check() {  # what, image, expected, tolerance
  local figures
  if ! figures=$("$btflut" compare "$2" "$3" --tolerance "$4"); then
    echo "$1: $figures" >&2
    exit 1
  fi
  echo "$1: $figures"
}

for entry in "${banks[@]}"; do
  IFS='|' read -r name bake tolerance view <<<"$entry"
  # shellcheck disable=SC2086
  "$btflut" bake $bake -o "$work/$name.btflut" -q
  "$btflut" export "$work/$name.btflut" -o "$work/$name" --web "$work/$name.html" -q
  # shellcheck disable=SC2086
  "$btflut" relight "$work/$name.btflut" --grid --light "$light" $view -o "$work/$name-grid.png" -q
  read -r width height channels < <(/usr/bin/python3 -c "import json,sys; r=json.load(open(sys.argv[1]))['reference']; print(r['width'], r['height'], r['channels'])" "$work/$name/material.json")

  page=$(stat -c %s "$work/$name.html")
  files=$(du -cb "$work/$name"/* | tail -1 | cut -f1)
  ratio=$(/usr/bin/python3 -c "print(f'{$page / $files:.2f}')")
  echo "export --web, $name: $page bytes, $ratio x the engine export's $files"
  /usr/bin/python3 -c "import sys; sys.exit(0 if $page <= 1.4 * $files else 1)" || { echo "the page is over 1.4 x the export" >&2; exit 1; }
  bash "$repo/tools/browser-shot.sh" "file://$work/$name.html#light=$light&zoom=1&ui=0" "$width" "$height" "$work/$name-web.png"
  crop "$work/$name-web.png" "$width" "$height" "$channels" "$work/$name-web-crop.png"
  check "export --web, $name at $light" "$work/$name-web-crop.png" "$work/$name-grid.png" "$tolerance"

  bash "$repo/tools/browser-shot.sh" "file://$repo/examples/three/relight.html#material=file://$work/$name/&light=$light" \
    "$width" "$height" "$work/$name-three.png"
  crop "$work/$name-three.png" "$width" "$height" "$channels" "$work/$name-three-crop.png"
  check "three.js r111 (Debian), $name at $light" "$work/$name-three-crop.png" "$work/$name-grid.png" "$tolerance"
  # The export's own page (three.html, with the recipe's scripts beside it) with current three.js.
  bash "$repo/tools/browser-shot.sh" "file://$work/$name/three.html#light=$light&three=file://$three_module" \
    "$width" "$height" "$work/$name-three-module.png"
  crop "$work/$name-three-module.png" "$width" "$height" "$channels" "$work/$name-three-module-crop.png"
  check "three.js $three_version (npm, ES module), $name at $light" "$work/$name-three-module-crop.png" \
    "$work/$name-grid.png" "$tolerance"
done

# The page with its panel, and the sphere under the point light: drawn, no console message.
bash "$repo/tools/browser-shot.sh" "file://$work/hsh2.html#light=50,120&zoom=fit" 900 600 "$work/panel.png"
for name in references views; do  # views: each fragment's view picks its layer and feeds the decoder
  bash "$repo/tools/browser-shot.sh" "file://$work/$name.html#light=50,120&view=sphere" 900 600 "$work/sphere.png"
  /usr/bin/python3 - "$work/sphere.png" <<'PY'
import sys
from PIL import Image
image = Image.open(sys.argv[1]).convert("L")
centre = image.crop((400, 250, 500, 350))  # the sphere's middle, lit from the upper left
corner = image.crop((850, 550, 900, 600))  # off the sphere: black
assert max(centre.getdata()) > 40 and max(corner.getdata()) == 0, "the sphere view is not drawn"
PY
done
echo "export --web: the panel and the sphere view draw"
# The sphere wraps the sample, not its background: a bank baked with a round mask exports the
# largest rectangle inside it (material.json's "sample"), and the page's sphere wraps that.
/usr/bin/python3 - "$default" "$work/round.png" <<'PY'
import json, sys
from PIL import Image, ImageDraw
manifest = json.load(open(sys.argv[1] + "/btflut-dataset.json"))
first = Image.open(sys.argv[1] + "/" + manifest["images"][0]["file"])
mask = Image.new("L", first.size, 0)
ImageDraw.Draw(mask).ellipse((10, 20, first.size[0] - 30, first.size[1] - 10), fill=255)
mask.save(sys.argv[2])
PY
"$btflut" bake "$default" --predictor hsh2 --mask "$work/round.png" -o "$work/round.btflut" -q
"$btflut" export "$work/round.btflut" --web "$work/round.html" -o "$work/round/" -q
timeout 180 chromium --headless --no-sandbox --user-data-dir="$work/profile" --use-angle=swiftshader \
  --enable-unsafe-swiftshader --window-size=600,600 --virtual-time-budget=30000 \
  --dump-dom "file://$work/round.html#light=20,0&view=sphere&ui=0" >"$work/round-dom.html" 2>/dev/null
/usr/bin/python3 - "$work/round/material.json" "$work/round-dom.html" "$work/round.png" <<'PY'
import json, re, sys
from PIL import Image
sample = json.load(open(sys.argv[1])).get("sample")
assert sample, "material.json of a masked bank has no sample rectangle"
found = re.search(r'data-sphere-window="([0-9,]*)"', open(sys.argv[2]).read())
assert found, "the page wrote no data-sphere-window"
window = [int(v) for v in found.group(1).split(",")]
assert window == [sample[k] for k in ("x", "y", "width", "height")], (window, sample)
mask = Image.open(sys.argv[3])
x, y, w, h = window
assert min(mask.crop((x, y, x + w, y + h)).getdata()) == 255, "the rectangle leaves the mask"
assert w * h > 0.5 * mask.size[0] * mask.size[1] * 0.6, "the rectangle is far smaller than the mask"
print(f"export --web: the sphere wraps the mask's largest rectangle {window}")
PY
# "Fit" places the material in the area the panel leaves free, at three window sizes (the
# page writes where it drew the material and the panel: data-material, data-panel).
for size in 1200,800 400,800 900,600; do
  timeout 180 chromium --headless --no-sandbox --user-data-dir="$work/profile" --use-angle=swiftshader \
    --enable-unsafe-swiftshader --window-size="$size" --virtual-time-budget=30000 \
    --dump-dom "file://$work/hsh2.html#light=50,120&zoom=fit" >"$work/fit.html" 2>/dev/null
  /usr/bin/python3 - "$size" "$work/fit.html" <<'PY' || exit 1
import re, sys
dom = open(sys.argv[2]).read()
width, height = map(int, sys.argv[1].split(","))
found = {k: re.search(r'data-%s="([-0-9,]*)"' % k, dom) for k in ("material", "panel", "size")}
assert all(found.values()), "the page wrote no data-material, data-panel or data-size"
m = [int(v) for v in found["material"].group(1).split(",")]
p = [int(v) for v in found["panel"].group(1).split(",")]
width, height = map(int, found["size"].group(1).split(","))  # the view (a browser's window has a least size)
overlap = max(0, min(m[2], p[2]) - max(m[0], p[0])) * max(0, min(m[3], p[3]) - max(m[1], p[1]))
inside = m[0] >= 0 and m[1] >= 0 and m[2] <= width and m[3] <= height
print(f"export --web, fit in a {sys.argv[1]} window ({width}x{height} view): the material at {m}, the panel at {p}, "
      f"{overlap} px under it")
if overlap > 0 or not inside or m[2] - m[0] < 32:
    sys.exit(f"export --web, fit in a {sys.argv[1]} window: the material is under the panel or off the page")
PY
done
# A light beyond the measured ones: the panel says "clamped", as relight, info and the viewer do.
dom=$(timeout 180 chromium --headless --no-sandbox --user-data-dir="$work/profile" --use-angle=swiftshader --enable-unsafe-swiftshader \
      --virtual-time-budget=30000 --dump-dom "file://$work/hsh2.html#light=88,0" 2>/dev/null)
# (the light's line, not the page's script, which holds the same words)
grep -q 'id="light">[^<]*clamped: beyond the measured lights; bake --fill model' <<<"$dom" ||
  { echo "export --web: a light beyond the measured ones is not said to be clamped" >&2; exit 1; }
echo "export --web: a light beyond the measured ones is said to be clamped"
# The panel names the predictor as bake and info do.
for pair in "neural5|learned (neural5)" "hsh2|model (hsh2)" "references|references (references)"; do
  IFS='|' read -r name label <<<"$pair"
  dom=$(timeout 180 chromium --headless --no-sandbox --user-data-dir="$work/profile" --use-angle=swiftshader \
        --enable-unsafe-swiftshader --virtual-time-budget=30000 --dump-dom "file://$work/$name.html" 2>/dev/null)
  grep -q "texels, $label," <<<"$dom" || { echo "export --web, $name: the panel does not say '$label'" >&2; exit 1; }
done
echo "export --web: the panel names each bank's predictor"
# Without #light a page opens at a light the capture measured around, never a clamped one
# (psm-rock's lights do not reach (30, 45)); the legend names the interpolated area.
if [ -f "$work/rock-rgb.html" ]; then
  dom=$(timeout 180 chromium --headless --no-sandbox --user-data-dir="$work/profile" --use-angle=swiftshader \
        --enable-unsafe-swiftshader --virtual-time-budget=30000 --dump-dom "file://$work/rock-rgb.html" 2>/dev/null)
  grep -q 'id="light">theta' <<<"$dom" && ! grep -q 'id="light">[^<]*clamped' <<<"$dom" ||
    { echo "export --web: psm-rock's page opens at a clamped light" >&2; exit 1; }
  grep -q 'dark: interpolated between them' <<<"$dom" || { echo "export --web: the legend omits the interpolated area" >&2; exit 1; }
  echo "export --web: psm-rock's page opens at a measured light"
fi
# Without WebGL2: a message, not a blank canvas.
dom=$(timeout 120 chromium --headless --no-sandbox --user-data-dir="$work/profile" --disable-webgl --disable-3d-apis \
      --virtual-time-budget=10000 --dump-dom "file://$work/one.html" 2>/dev/null)
grep -q 'This page needs WebGL2' <<<"$dom" || { echo "export --web: no message where WebGL2 is missing" >&2; exit 1; }
echo "export --web: without WebGL2 the page says so"
