#!/usr/bin/env bash
# `curio-lab run` stopped by Ctrl-C (SIGINT), then by SIGTERM, part way:
# exit 130 / 143, the finished runs' records on disk (no half file), a message with the count
# and how to resume; each rerun skips the recorded runs, and the last one ends with the report
# of an uninterrupted campaign, file for file (wall times aside).
#   tests/lab/interrupt.sh CURIO_LAB WORK_DIR
set -euo pipefail
lab=$1 work=$2
. "$(dirname "$0")/report_compare.sh"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $*"; for f in err*.txt; do echo "== $f"; cat "$f"; done; exit 1; }
opts=(--algos MGE-EFR --seeds 0-11 --episodes 3000 --threads 1 --quiet)
records() { ls camp/records/ 2> /dev/null | grep -c '\.cbor$' || true; }

"$lab" run "${opts[@]}" --out whole > /dev/null 2> err0.txt || fail "uninterrupted run failed"

# Starts the campaign into camp/, sends signal $1 once $2 runs are recorded; checks the exit
# status $3 and the message.
interrupt() {
  local sig=$1 at=$2 want=$3 log=$4 pid rc=0 n
  "$lab" run "${opts[@]}" --out camp > /dev/null 2> "$log" &
  pid=$!
  for _ in $(seq 1500); do (($(records) >= at)) && break; sleep 0.02; done
  kill -0 "$pid" 2> /dev/null || fail "SIG$sig: curio-lab ended before the signal (exit: see $log)"
  kill -"$sig" "$pid"
  wait "$pid" || rc=$?
  [[ $rc == "$want" ]] || fail "SIG$sig: exit $rc, not $want"
  n=$(records)
  ((n >= at && n < 12)) || fail "SIG$sig: $n records (at least $at, fewer than 12 expected)"
  grep -q "stopped by SIG$sig: $n of 12 runs finished and recorded in camp/records" "$log" ||
    fail "SIG$sig: no stop message with the count"
  grep -q "Run the same command again to resume" "$log" || fail "no resume hint"
  [[ ! -e camp/summary.json ]] || fail "a report was written for an unfinished campaign"
  no_temp_files camp
  echo "SIG$sig after $at records: exit $rc, $n of 12 runs recorded"
  stopped_at=$n
}

interrupt INT 2 130 err1.txt
before=$(stat -c '%n %i %Y' camp/records/*.cbor)
interrupt TERM $((stopped_at + 2)) 143 err2.txt
grep -q "resuming camp: $(echo "$before" | wc -l) of 12 runs recorded (skipped)" err2.txt ||
  fail "the second start did not resume"
for f in $(echo "$before" | cut -d' ' -f1); do
  grep -qx "$(stat -c '%n %i %Y' "$f")" <<< "$before" || fail "$f was written again"
done
"$lab" run "${opts[@]}" --out camp > /dev/null 2> err3.txt || fail "the last rerun failed"
grep -q "resuming camp: $stopped_at of 12 runs recorded (skipped), $((12 - stopped_at)) to run" err3.txt ||
  fail "the last start did not resume"
same_report whole camp
echo "interrupted twice, resumed: report equal to the uninterrupted campaign's"
