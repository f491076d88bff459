#!/usr/bin/env bash
# Faults never change results silently, tried as a user would: `curio-sim
# serve` and `curio-controller` as processes on the UDP bus (seed 0, MGE-EFR, ODE).
#   bus_faults.sh CURIO_SIM CURIO_CONTROLLER WORKDIR SCENARIO
# SCENARIO:
#   second_controller  a second controller started beside a running one refuses to start
#                      (exit 1, "another master"); the first finishes undisturbed (same
#                      archive checksum as an undisturbed run, exit 0)
#   second_serve       two serves on one bus: the controller stops ("two nodes answer")
#   restart:DELAY      serve killed (SIGKILL) mid-run and restarted after DELAY s: the run
#                      recovers with the undisturbed run's checksum, exit 0, and its
#                      summary.json records the replay and the 8 node reboots
set -euo pipefail
sim=$1 controller=$2 work=$3 scenario=$4
episodes=800
rm -rf "$work" && mkdir -p "$work"
port=$(/usr/bin/python3 "$(dirname "$0")/../common/free_udp_ports.py" 4 $$)
[ -n "$port" ] || { echo "no 4 free UDP ports on 127.0.0.1"; exit 1; }
bus="udp:127.0.0.1:$port?ports=4"
pids=()
trap 'for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done' EXIT

serve() {  # serve LOG: starts one, its PID in $serve_pid
  "$sim" serve --bus "$bus" --seed 0 --exit-after-idle 30 --status-every 0 2> "$1" &
  serve_pid=$!
  pids+=("$serve_pid")
}
run_controller() {  # run_controller NAME: foreground; rc in $rc
  rc=0
  "$controller" --bus "$bus" --seed 0 --episodes $episodes --out "$work/$1" --print-checksum \
    --progress-every 0.1 > "$work/$1.out" 2> "$work/$1.err" || rc=$?
}
checksum() { grep -o 'archive checksum 0x[0-9a-f]*' "$work/$1.out" || true; }
wait_progress() {  # wait_progress NAME: until its first progress line (the run is under way)
  for _ in $(seq 1 300); do
    grep -q ' episodes, ratio' "$work/$1.err" 2>/dev/null && return 0
    sleep 0.05
  done
  echo "no progress from $1:"; cat "$work/$1.err"; exit 1
}
wait_serving() {  # wait_serving LOG: until that serve is on the bus (its banner is written then)
  for _ in $(seq 1 300); do
    grep -q ' physics, seed ' "$1" 2>/dev/null && return 0
    sleep 0.05
  done
  echo "serve did not start:"; cat "$1"; exit 1
}
fail() { echo "FAIL: $*"; for f in "$work"/*.err "$work"/*.log; do echo "== $f"; tail -n 5 "$f"; done; exit 1; }

# The undisturbed run first: the reference.
reference() {
  serve "$work/serve0.log"
  run_controller reference
  [ $rc -eq 0 ] || fail "undisturbed run: exit $rc"
  kill -INT "$serve_pid"; wait "$serve_pid" || true
  want=$(checksum reference)
  [ -n "$want" ] || fail "no checksum from the undisturbed run"
}

case $scenario in
  second_controller)
    reference
    serve "$work/serve.log"
    run_controller first & first=$!
    wait_progress first
    run_controller second
    [ $rc -eq 1 ] || fail "the second controller: exit $rc, want 1"
    grep -q "another master is on this bus" "$work/second.err" || fail "second: no 'another master'"
    rc=0; wait $first || rc=$?
    [ $rc -eq 0 ] || fail "the first controller: exit $rc, want 0"
    [ "$(checksum first)" = "$want" ] || fail "first: $(checksum first), undisturbed $want"
    echo "second controller refused; the first run is undisturbed ($want)"
    ;;
  second_serve)
    # Both arms on the bus before the controller starts (the scenario): a serve that starts
    # after the controller is a second arm booting mid-run, which shows as other faults.
    serve "$work/serve1.log"
    serve "$work/serve2.log"
    wait_serving "$work/serve1.log"
    wait_serving "$work/serve2.log"
    run_controller two_serves
    [ $rc -eq 1 ] || fail "controller beside two serves: exit $rc, want 1"
    grep -q "two nodes answer as node" "$work/two_serves.err" || fail "no 'two nodes answer'"
    [ ! -e "$work/two_serves/summary.json" ] || fail "results written beside two arms"
    echo "two serves on one bus: the controller refused ($(grep -o 'two nodes answer as node [0-9]*' "$work/two_serves.err"))"
    ;;
  restart:*)
    delay=${scenario#restart:}
    reference
    serve "$work/serve1.log"
    run_controller restarted & ctl=$!
    wait_progress restarted
    kill -9 "$serve_pid"
    sleep "$delay"
    serve "$work/serve2.log"
    rc=0; wait $ctl || rc=$?
    [ $rc -eq 0 ] || fail "controller after a $delay s serve restart: exit $rc, want 0"
    [ "$(checksum restarted)" = "$want" ] || fail "restarted: $(checksum restarted), undisturbed $want"
    s="$work/restarted/summary.json"
    grep -q '"node_reboots": 8' "$s" || fail "summary.json does not record the 8 node reboots"
    grep -q '"results": "exact"' "$s" || fail "summary.json does not say exact"
    grep -Eq '"replays": [1-9]' "$s" || fail "summary.json records no replay"
    grep -q "8 node reboots" "$work/restarted/summary.md" || fail "summary.md silent"
    echo "serve restarted after $delay s: undisturbed results ($want), reboots and replays recorded"
    ;;
  *)
    echo "unknown scenario '$scenario'"; exit 2 ;;
esac
