#!/usr/bin/env bash
# One run of a campaign stopped part way (Ctrl-C, then SIGKILL) resumes
# from its journal (records/run-0.journal): the restart replays the journaled episodes and
# continues at the next one, and the campaign ends with the report of an uninterrupted run,
# file for file (wall times aside); the journal is removed once the run's record is written.
#   tests/lab/resume_run.sh CURIO_LAB WORK_DIR
set -euo pipefail
lab=$1 work=$2
. "$(dirname "$0")/report_compare.sh"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $*"; for f in err*.txt; do echo "== $f"; cat "$f"; done; exit 1; }
opts=(--algos MGE-EFR --seeds 0 --physics ode --episodes 1500 --threads 1 --quiet)
journal=camp/records/run-0.journal
size() { stat -c %s "$journal" 2> /dev/null || echo 0; }

"$lab" run "${opts[@]}" --out whole > /dev/null 2> err0.txt || fail "uninterrupted run failed"

# Starts the run into camp/, sends signal $1 once the journal holds $2 bytes more than now.
interrupt() {
  local sig=$1 grow=$2 want=$3 log=$4 pid rc=0 from
  from=$(size)
  "$lab" run "${opts[@]}" --out camp > /dev/null 2> "$log" &
  pid=$!
  for _ in $(seq 1500); do (($(size) >= from + grow)) && break; sleep 0.01; done
  kill -0 "$pid" 2> /dev/null || fail "SIG$sig: curio-lab ended before the signal (exit: see $log)"
  kill -"$sig" "$pid"
  wait "$pid" || rc=$?
  [[ $rc == "$want" ]] || fail "SIG$sig: exit $rc, not $want"
  [[ ! -e camp/records/run-0.cbor && -s $journal ]] || fail "SIG$sig: finished, or no journal"
  echo "SIG$sig: exit $rc, journal $(size) bytes"
}

interrupt INT 20000 130 err1.txt
grep -q "stopped by SIGINT: 0 of 1 runs finished" err1.txt || fail "no stop message"
interrupt KILL 20000 137 err2.txt
grep -q "resumed from $journal: .* episodes journaled; continuing at episode" err2.txt ||
  fail "the second start did not resume from the journal"
"$lab" run "${opts[@]}" --out camp > /dev/null 2> err3.txt || fail "the last start failed"
at=$(sed -n 's/.*continuing at episode \([0-9]*\).*/\1/p' err3.txt)
first=$(sed -n 's/.*continuing at episode \([0-9]*\).*/\1/p' err2.txt)
((at > first && first > 0)) || fail "resumed at $first then $at episodes"
[[ ! -e $journal ]] || fail "the journal is still there after the run's record"
same_report whole camp
echo "stopped at episode $first (SIGINT) and $at (SIGKILL), resumed: report equal to the uninterrupted run's"
