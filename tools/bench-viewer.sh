#!/usr/bin/env bash
# The viewer's frame time and idle CPU under Xvfb on llvmpipe (issue 15's targets):
#  - a 1920 x 1080 window, the default material in 2D mode, the light moving every frame
#    (`view --light-sweep --timing`: median and 90th percentile of 60 frames, the first left
#    out, swap included, vsync off); also with a wipe and with exposure (a pass more each);
#  - idle: the interactive viewer left alone for 5 s after it settles: CPU seconds used
#    (target 0: it waits for events instead of drawing).
set -euo pipefail
cd "$(dirname "$0")/.."
btflut="${BTFLUT:-build/btflut}"
xvfb=(xvfb-run -a -s "-screen 0 1920x1080x24")
for extra in "" "--compare wipe" "--exposure 1"; do
  printf '%-16s ' "${extra:-default}"
  "${xvfb[@]}" "$btflut" view --size 1920x1080 --frames 61 --light-sweep --no-vsync --timing $extra | grep "view timing"
done
# Idle: the process's CPU time (utime + stime, clock ticks) over 5 s with no input.
"${xvfb[@]}" bash -c '
  "$0" view --size 1920x1080 & pid=$!
  sleep 6
  ticks() { awk "{ print \$14 + \$15 }" /proc/$pid/stat; }
  before=$(ticks); sleep 5; after=$(ticks)
  kill $pid; wait $pid 2>/dev/null || true
  echo "idle: $(( after - before )) clock ticks of CPU in 5 s (1 tick = 1/$(getconf CLK_TCK) s); target 0"
' "$btflut"
