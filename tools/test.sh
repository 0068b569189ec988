#!/usr/bin/env bash
# Sets up, builds with warnings as errors, and runs every test: the scikit-image agreement
# check, then the doctest suite through CTest. Tests that need ../shared/data skip when it
# is missing, unless BTFLUT_REQUIRE_DATA=1 (CI sets it), which makes that a failure.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
bash tools/build.sh -DBTFLUT_WERROR=ON
data="${BTFLUT_DATA:-../shared/data}"
folders=(build/assets/default)
if [ -d "$data/psm-rock" ]; then
  folders+=("$data/psm-rock")
elif [ "${BTFLUT_REQUIRE_DATA:-0}" = 1 ]; then
  echo "test: $data/psm-rock is missing (set BTFLUT_DATA)" >&2
  exit 1
fi
/usr/bin/python3 tools/compare_skimage.py build/btflut "${folders[@]}"
cd build && ctest --output-on-failure
