#!/usr/bin/env bash
# Configures and builds btflut in ./build (Release), or in $BTFLUT_BUILD_DIR. Extra
# arguments go to CMake's configure.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${BTFLUT_BUILD_DIR:-build}"
# Ninja for a new build folder: it keeps both cores busy across targets, where make's
# recursion waits for each library (a first build 244 s with make, 184 s with Ninja).
generator=()
[ -f "$build/CMakeCache.txt" ] || ! command -v ninja >/dev/null || generator=(-G Ninja)
cmake -S . -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build" -j "$(nproc)"
