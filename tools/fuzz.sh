#!/usr/bin/env bash
# Fuzzes every parser btflut has (tests/fuzz/fuzz_targets.h) with libFuzzer, AddressSanitizer
# and UndefinedBehaviorSanitizer, SECONDS per target (default 60), two targets at a time:
#
#   bash tools/fuzz.sh [SECONDS] [TARGET ...]
#
# Builds with clang in build-fuzz/, seeds each target from real files (tools/fuzz_seeds.py,
# with ../shared/data when it is there) and the committed regression inputs
# (tests/fuzz/regressions/TARGET/), and keeps what it learns in build-fuzz/corpus/TARGET/.
# Fails on any finding: a crash, a sanitizer report, a leak, an input slower than 20 s or
# one that needs more than 2 GiB; the input is left in build-fuzz/findings/ and its log in
# build-fuzz/logs/. Prints executions per target.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(bank image lp lights manifest scene histograms params names)

bash tools/setup.sh >/dev/null
[ -x build/btflut ] || bash tools/build.sh >/dev/null  # the seeds are made by btflut itself
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBTFLUT_FUZZ=ON \
  -DBTFLUT_BUILD_TESTS=OFF >/dev/null
cmake --build build-fuzz --target btflut_fuzzers -j "$(nproc)" >/dev/null
rm -rf build-fuzz/seeds build-fuzz/findings build-fuzz/logs
mkdir -p build-fuzz/findings build-fuzz/logs
/usr/bin/python3 tools/fuzz_seeds.py build/btflut build-fuzz/seeds "${BTFLUT_DATA:-../shared/data}"

fuzz_one() {
  local t="$1" seconds="$2"
  mkdir -p "build-fuzz/corpus/$t" "build-fuzz/seeds/$t"
  local inputs=("build-fuzz/corpus/$t" "build-fuzz/seeds/$t")
  [ -d "tests/fuzz/regressions/$t" ] && inputs+=("tests/fuzz/regressions/$t")
  if "build-fuzz/tests/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 \
      -max_len=65536 -print_final_stats=1 -artifact_prefix="build-fuzz/findings/$t-" \
      "${inputs[@]}" >"build-fuzz/logs/$t.log" 2>&1; then
    printf 'fuzz %-10s ok: %s executions in %s s\n' "$t" \
      "$(grep -o 'stat::number_of_executed_units: *[0-9]*' "build-fuzz/logs/$t.log" | grep -o '[0-9]*$')" "$seconds"
  else
    printf 'fuzz %-10s FINDING: see build-fuzz/logs/%s.log and build-fuzz/findings/\n' "$t" "$t"
    return 1
  fi
}
export -f fuzz_one
printf '%s\n' "${targets[@]}" | xargs -P "$(nproc)" -I{} bash -c "fuzz_one {} $seconds"
