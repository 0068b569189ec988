#!/usr/bin/env bash
# The main job on the bundled default material: set up, build, bake its LUT bank, and
# relight the reference image for a grazing light. Prints where everything went.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
bash tools/build.sh >/dev/null
mkdir -p out
./build/btflut bake build/assets/default -o out/default.btflut
./build/btflut info out/default.btflut
./build/btflut relight out/default.btflut --light 50,30 -o out/default-relit-50-30.png
echo "relit image: $(pwd)/out/default-relit-50-30.png (bank: $(pwd)/out/default.btflut)"
