#!/usr/bin/env bash
# Installs the Debian packages btflut needs to build, test and run (Debian 12, as root or
# with sudo). Idempotent: packages already present are left alone, and `apt-get update` runs
# only when something is missing. Nothing is downloaded from anywhere but Debian's archive.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libstb-dev            # stb_image (decodes TGA and BMP)
  libspng-dev zlib1g-dev  # PNG decode and encode (8/16-bit), CRC-32 for .btflut files
  libturbojpeg0-dev     # JPEG decode (libjpeg-turbo)
  libqhull-dev          # Delaunay triangulation of measured directions (2-D and 3-D)
  libcli11-dev nlohmann-json3-dev doctest-dev
  libfftw3-dev          # spectral synthesis of rough height fields
  libeigen3-dev         # least squares (PTM fitting)
  libceres-dev          # non-linear least squares (btflut fit)
  libglm-dev libglfw3-dev libosmesa6-dev libegl-dev libgl-dev libimgui-dev
  libopengl-dev         # libOpenGL (glvnd): the example engine program links it, not btflut
  python3 python3-numpy python3-skimage python3-pil  # reference checks in tools/
  xvfb xauth
  glslang-tools spirv-cross  # the include's HLSL and GLSL ES forms (tools/shader-forms.sh)
  mono-mcs              # parses and runs the Unity example's C# (tests/engine_examples_check.sh)
  chromium libjs-three  # WebGL2 tests in headless Chromium: the three.js recipe
  parallel              # GNU parallel: tools/bake-library.sh bakes materials side by side
  clang libclang-rt-14-dev  # libFuzzer and the sanitizer runtimes (tools/fuzz.sh)
  clang-format          # the code's format (tools/format.sh; tools/test.sh checks it)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# npm fetches current three.js for the recipe's test (tests/browser_check.sh): Debian's npm,
# unless a Node.js that ships its own (NodeSource's nodejs) is there, which Debian's would conflict with.
command -v npm >/dev/null || missing+=(npm)
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
