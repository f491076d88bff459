#!/usr/bin/env bash
# Runs a test command N times with BUSY busy loops beside it (default 2: both cores of a CI
# machine taken), and prints how many runs passed; exit 1 if any failed (its output is kept
# in WORK/fail-<i>.log). For the multi-process tests, whose timing a loaded machine changes:
#   tests/common/under_load.sh 50 /tmp/load -- ctest --test-dir build/default -R app_two_process_udp
#   BUSY=3 tests/common/under_load.sh 20 /tmp/load -- bash tests/app/bus_faults.sh ...
set -euo pipefail
n=$1 work=$2
shift 2
[ "${1:-}" = "--" ] && shift
busy=${BUSY:-2}
rm -rf "$work" && mkdir -p "$work"
loops=()
trap 'kill "${loops[@]}" 2>/dev/null || true' EXIT
for _ in $(seq 1 "$busy"); do
  (while :; do :; done) &
  loops+=($!)
done
passed=0
for i in $(seq 1 "$n"); do
  if "$@" > "$work/run.log" 2>&1; then
    passed=$((passed + 1))
  else
    cp "$work/run.log" "$work/fail-$i.log"
    echo "run $i failed: $work/fail-$i.log"
  fi
done
echo "$passed of $n passed with $busy busy loops beside them"
[ "$passed" = "$n" ]
