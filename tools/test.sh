#!/usr/bin/env bash
# Sets up, checks the format, builds with warnings as errors, and runs every test: the scikit-image agreement
# check, then the doctest suite, the viewer under Xvfb and the hostile inputs through CTest.
# Tests that need ../shared/data skip when it is missing, unless BTFLUT_REQUIRE_DATA=1 (CI
# sets it), which makes that a failure.
#
#   bash tools/test.sh              # build/ (Release)
#   bash tools/test.sh --sanitize   # build-asan/: everything under AddressSanitizer and
#                                   # UndefinedBehaviorSanitizer, leaks checked (only Mesa's
#                                   # own are suppressed: tests/sanitizers/lsan.supp)
set -euo pipefail
cd "$(dirname "$0")/.."
build=build
configure=(-DBTFLUT_WERROR=ON)
if [ "${1:-}" = "--sanitize" ]; then
  build=build-asan
  configure+=(-DBTFLUT_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo)
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0
  export LSAN_OPTIONS="suppressions=$(pwd)/tests/sanitizers/lsan.supp:print_suppressions=0"
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  export BTFLUT_SANITIZED=1  # tests/bombs.py: shadow memory is not the program's
fi
bash tools/setup.sh
bash tools/format.sh --check  # clang-format --dry-run --Werror: the code as .clang-format lays it out
BTFLUT_BUILD_DIR="$build" bash tools/build.sh "${configure[@]}"
data="${BTFLUT_DATA:-../shared/data}"
folders=("$build/assets/default")
if [ -d "$data/psm-rock" ]; then
  folders+=("$data/psm-rock")
elif [ "${BTFLUT_REQUIRE_DATA:-0}" = 1 ]; then
  echo "test: $data/psm-rock is missing (set BTFLUT_DATA)" >&2
  exit 1
fi
/usr/bin/python3 tools/compare_skimage.py "$build/btflut" "${folders[@]}"
# Two at a time (as many as there are cores): the unit suite's training runs on one core for
# long stretches, and the GL, viewer and browser checks fit beside it (each has its own
# temporary folders and X display); under the sanitizers this halves the suite's time.
cd "$build" && ctest --output-on-failure -j "$(nproc)"
