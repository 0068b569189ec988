#!/usr/bin/env bash
# A screenshot of a page in headless Chromium (Debian's `chromium`; WebGL2 on its SwiftShader
# software renderer), failing with the browser's own lines when the page logs anything to its
# console (the pages here log only errors) or WebGL reports an error.
#
#   bash tools/browser-shot.sh URL WIDTH HEIGHT OUT.png
set -euo pipefail
url=$1 width=$2 height=$3 out=$4
command -v chromium >/dev/null || { echo "browser-shot: chromium not found (bash tools/setup.sh installs it)" >&2; exit 1; }
log=$(mktemp)
profile=$(mktemp -d)
trap 'rm -rf "$log" "$profile"' EXIT
# Root (CI containers) needs --no-sandbox. --virtual-time-budget lets the page's loading finish
# before the screenshot is taken.
if ! timeout 180 chromium --headless --no-sandbox --user-data-dir="$profile" --use-angle=swiftshader \
    --enable-unsafe-swiftshader --allow-file-access-from-files --force-device-scale-factor=1 --hide-scrollbars \
    --window-size="$width,$height" --virtual-time-budget=60000 --enable-logging=stderr --v=0 \
    --screenshot="$out" "$url" >"$log" 2>&1; then
  cat "$log" >&2
  echo "browser-shot: chromium failed on $url" >&2
  exit 1
fi
if grep -E "CONSOLE|GL_INVALID|WebGL-|GPU process isn't usable" "$log" >&2; then
  echo "browser-shot: $url: the lines above came from the page" >&2
  exit 1
fi
[ -s "$out" ] || { echo "browser-shot: no screenshot of $url" >&2; exit 1; }
