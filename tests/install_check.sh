#!/usr/bin/env bash
# `cmake --install` into a temporary prefix: the installed btflut says its version, the shader
# include and the default material are in place, and the installed viewer opens the default
# material (one scripted frame under Xvfb) with no path compiled in. A fixed predictor: how the
# viewer bakes by default (auto) is viewer_smoke.py's subject.
set -euo pipefail
build="$1"
prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
cmake --install "$build" --prefix "$prefix" >/dev/null
"$prefix/bin/btflut" --version | grep -q "^btflut [0-9]"
for include in btflut.glsl btflut_es.glsl btflut.hlsl btflut.gdshaderinc; do test -f "$prefix/share/btflut/shaders/$include"; done
test -f "$prefix/share/btflut/default/btflut-dataset.json"
test -f "$prefix/share/doc/btflut/LICENSE"
# Away from the build tree, so nothing but the installed layout can be found.
cd "$prefix"
env -u BTFLUT_DEFAULT_MATERIAL xvfb-run -a -s "-screen 0 1280x1024x24" \
  "$prefix/bin/btflut" view --predictor hsh2 --frames 2 --screenshot "$prefix/shot.png" >/dev/null 2>&1
test -s "$prefix/shot.png"
echo "installed into a temporary prefix: version, shader include, default material and the viewer work"
