#!/usr/bin/env bash
# Configures and builds btflut in ./build (Release), or in $BTFLUT_BUILD_DIR. Extra
# arguments go to CMake's configure.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${BTFLUT_BUILD_DIR:-build}"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build" -j "$(nproc)"
