#!/usr/bin/env bash
# Runs the parts of `fetic-bench-scale --preset full` for two binaries, alternating, so
# that a loaded machine hits both alike: every part is its own process, in rounds of
# old, new, new, old. Each run writes its CSVs and `/usr/bin/time -f "%e %M %U %S %x"`
# (wall s, peak kB, user s, system s, exit status) into
# OUT/<part>/<round>.<slot>.<old|new>/; OUT/load.txt gets the time and /proc/loadavg
# every 15 s. scripts/compare_tables.py OUT reads it all.
#
#   scripts/bench_tables.sh OLD_BENCH NEW_BENCH OUT [ROUNDS [PART...]]
#
# ROUNDS (default 2) rounds of every PART (default: comparison bytes subdomains pressed
# refinement memory frames), round by round. Runs already in OUT are kept and their
# rounds skipped, so the script can be started again to add rounds. A part listed twice
# gets two rounds per round (cheap parts: more pairs). Runs of `bytes` (the old binary
# peaks at 4 GB) take `flock /work/big.lock`, so that no two big
# runs overlap; STOP_AT=HH:MM (UTC) ends the script before a run would start later;
# PRESET=quick tries the script out in a minute.
set -euo pipefail

if [[ $# -lt 3 ]]; then
  sed -n '2,18p' "$0"
  exit 2
fi
old=$(realpath "$1")
new=$(realpath "$2")
out=$3
rounds=${4:-2}
shift $(($# < 4 ? $# : 4))
parts=("$@")
[[ ${#parts[@]} -gt 0 ]] || parts=(comparison bytes subdomains pressed refinement memory frames)
mkdir -p "$out"

(while true; do
  echo "$(date -u +%T) $(cut -d' ' -f1-3 /proc/loadavg)" >>"$out/load.txt"
  sleep 15
done) &
logger=$!
trap 'kill $logger' EXIT

past_stop() {
  [[ -n ${STOP_AT:-} ]] && [[ $(date -u +%H:%M) > $STOP_AT || $(date -u +%H:%M) == "$STOP_AT" ]]
}

run_one() { # part, directory, binary
  local part=$1 dir=$2 binary=$3 lock=()
  if [[ $part == bytes ]]; then
    lock=(flock /work/big.lock)
  fi
  mkdir -p "$dir"
  echo "$(date -u +%T) start $dir" >>"$out/runs.txt"
  "${lock[@]}" /usr/bin/time -f "%e %M %U %S %x" -o "$dir/time.txt" \
    "$binary" --preset "${PRESET:-full}" --only "$part" --csv-dir "$dir" >"$dir/stdout.txt" 2>"$dir/stderr.txt" ||
    true
  echo "$(date -u +%T) end $dir $(cat "$dir/time.txt" | tail -1)" >>"$out/runs.txt"
}

for ((r = 1; r <= rounds; ++r)); do
  declare -A seen=()
  for part in "${parts[@]}"; do
    seen[$part]=$((${seen[$part]:-0} + 1))
    # Round numbers of a part listed twice: 1, 2 in the first round, 3, 4 in the second.
    count=0
    for p in "${parts[@]}"; do [[ $p == "$part" ]] && count=$((count + 1)); done
    round=$(((r - 1) * count + seen[$part]))
    [[ -e $out/$part/$round.4.old/time.txt ]] && continue
    slot=0
    for version in old new new old; do
      slot=$((slot + 1))
      dir=$out/$part/$round.$slot.$version
      [[ -e $dir/time.txt ]] && continue
      if past_stop; then
        echo "STOP_AT $STOP_AT reached" >>"$out/runs.txt"
        exit 0
      fi
      binary=$old
      [[ $version == new ]] && binary=$new
      run_one "$part" "$dir" "$binary"
    done
  done
  unset seen
done
