#!/usr/bin/env bash
# Bakes a library of materials, one dataset per subfolder, into one bank each, side by side
# (each material's bake is independent of every other's), then writes a summary table.
#
#   tools/bake-library.sh LIBRARY OUT [--jobs N] [-- BAKE OPTIONS ...]   all, with GNU parallel
#   tools/bake-library.sh --one MATERIAL OUT [-- BAKE OPTIONS ...]        one (a Slurm array task)
#   tools/bake-library.sh --summary OUT                                   the table of what is in OUT
#
# OUT gets NAME.btflut per material, status/NAME.tsv per attempt and summary.md (material,
# result, seconds, bytes, and the error line of each failure). Exit status 1 when a material
# failed. The btflut program: $BTFLUT, else build/btflut. On a cluster see
# tools/bake-library.slurm (docs/datasets.md, "Baking a library").
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
btflut="${BTFLUT:-$here/build/btflut}"

bake_one() {  # MATERIAL OUT [BAKE OPTIONS]
  local material="${1%/}" out="$2"; shift 2
  local name; name="$(basename "$material")"
  mkdir -p "$out/status"
  local start=$EPOCHREALTIME
  local error=""
  if ! error=$("$btflut" bake "$material" -o "$out/$name.btflut" -q "$@" 2>&1); then
    printf '%s\tfailed\t%.1f\t0\t%s\n' "$name" "$(awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { print b - a }')" "$(echo "$error" | tail -n 1)" \
      >"$out/status/$name.tsv"
    return 1
  fi
  printf '%s\tok\t%.1f\t%s\t\n' "$name" "$(awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { print b - a }')" "$(stat -c %s "$out/$name.btflut")" \
    >"$out/status/$name.tsv"
}

summary() {  # OUT
  local out="$1" failed=0 ok=0
  {
    echo "| material | result | seconds | bytes | error |"
    echo "| --- | --- | --- | --- | --- |"
    for status in "$out"/status/*.tsv; do
      [ -e "$status" ] || continue
      IFS=$'\t' read -r name result seconds bytes error <"$status"
      echo "| $name | $result | $seconds | $bytes | ${error//|/\\|} |"
      if [ "$result" = ok ]; then ok=$((ok + 1)); else failed=$((failed + 1)); fi
    done
    echo
    echo "$ok baked, $failed failed"
  } >"$out/summary.md"
  cat "$out/summary.md"
  [ "$failed" -eq 0 ]
}

case "${1:-}" in
  --one) shift; material="$1" out="$2"; shift 2; [ "${1:-}" = "--" ] && shift; bake_one "$material" "$out" "$@"; exit ;;
  --summary) summary "$2"; exit ;;
  ""|-h|--help) sed -n '2,14p' "$0"; exit 2 ;;
esac

library="$1" out="$2"; shift 2
jobs="$(nproc)"
if [ "${1:-}" = "--jobs" ]; then jobs="$2"; shift 2; fi
[ "${1:-}" = "--" ] && shift
[ -d "$library" ] || { echo "bake-library: $library: not a folder" >&2; exit 2; }
mkdir -p "$out"
rm -rf "$out/status"
mapfile -t materials < <(find "$library" -mindepth 1 -maxdepth 1 -type d | sort)
[ "${#materials[@]}" -gt 0 ] || { echo "bake-library: $library: no material folders" >&2; exit 2; }
# GNU parallel runs the materials N at a time; a failure is recorded, the others go on.
parallel --will-cite --jobs "$jobs" bash "$0" --one {} "$out" -- "$@" ::: "${materials[@]}" || true
summary "$out"
