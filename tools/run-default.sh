#!/usr/bin/env bash
# The main job on the bundled default material: set up, build what it needs (the program
# and the default material; not the tests), bake its LUT bank, and relight the reference
# image for a grazing light. Prints where everything went.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
build="${BTFLUT_BUILD_DIR:-build}"
if [ ! -x "$build/btflut" ]; then
  echo "building btflut (the first build takes 3 to 4 minutes on 2 cores; later runs only what changed) ..."
fi
start=$(date +%s)
# Ninja for a new build folder: it keeps both cores busy across targets, where make's
# recursion waits for each library (a first build 244 s with make, 184 s with Ninja).
generator=()
[ -f "$build/CMakeCache.txt" ] || ! command -v ninja >/dev/null || generator=(-G Ninja)
cmake -S . -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release >/dev/null
# The program and the default material it renders at build time; the progress on one line,
# the compiler's output in a log shown when the build fails.
log="$build/build.log"
: >"$log"  # exists before the progress line first reads it
cmake --build "$build" -j "$(nproc)" --target btflut default_material >"$log" 2>&1 &
pid=$!
while kill -0 "$pid" 2>/dev/null; do
  printf "\r  building: %s " "$(grep -so '^\[[ 0-9/%]*\]' "$log" | tail -1)"
  sleep 2
done
if ! wait "$pid"; then
  echo; tail -n 30 "$log"; echo "the build failed (full log: $log)"; exit 1
fi
printf "\r%-40s\r" ""
echo "built in $(( $(date +%s) - start )) s"
mkdir -p out
"$build"/btflut bake "$build"/assets/default -o out/default.btflut
"$build"/btflut info out/default.btflut
"$build"/btflut relight out/default.btflut --light 50,30 -o out/default-relit-50-30.png
"$build"/btflut export out/default.btflut --web out/default.html -q
echo "relit image: $(pwd)/out/default-relit-50-30.png (bank: $(pwd)/out/default.btflut)"
echo "in a browser (WebGL2, no server): file://$(pwd)/out/default.html#light=50,30"
