#!/usr/bin/env bash
# SIGTERM, SIGINT and SIGHUP end curio-controller with a controlled stop, tried as a user would:
# `curio-sim serve` and `curio-controller` as processes on the UDP bus (kinematic, MGE-EFR,
# seed 3). For each signal, sent while the arm moves:
#   * the exit status is 128 + the signal (143, 130, 129) and the controller says it stopped by
#     that signal, how many whole episodes the journal keeps, and to resume with --resume;
#   * the controlled stop is on the bus before the controller exits: it reports all 7 joints
#     standing still and disabled, and the serve logs each joint's standstill after the quick
#     stop, in switch on disabled;
#   * `--resume` finishes the run with the uninterrupted run's archive checksum.
#   stop_signals.sh CURIO_SIM CURIO_CONTROLLER WORKDIR [EPISODES]
set -euo pipefail
sim=$1 controller=$2 work=$3 episodes=${4:-100}
seed=3
rm -rf "$work" && mkdir -p "$work"
port=$(/usr/bin/python3 "$(dirname "$0")/../common/free_udp_ports.py" 2 $$)
[ -n "$port" ] || { echo "no free UDP port pair on 127.0.0.1"; exit 1; }
bus="udp:127.0.0.1:$port?ports=2"
serve_pid="" ctl_pid=""
trap 'for p in $serve_pid $ctl_pid; do kill -9 "$p" 2>/dev/null || true; done' EXIT
fail() { echo "FAIL: $*"; for f in "$work"/*.err "$work"/*.log; do echo "== $f"; tail -n 6 "$f"; done; exit 1; }

"$sim" serve --bus "$bus" --physics kinematic --seed $seed --exit-after-idle 60 \
  --status-every 0 2> "$work/serve.log" &
serve_pid=$!
run() {  # run NAME [args...]: foreground; rc in $rc
  rc=0
  "$controller" --bus "$bus" --seed $seed --episodes "$episodes" --out "$work/$1" --print-checksum \
    --progress-every 0.1 "${@:2}" > "$work/$1.out" 2> "$work/$1.err" || rc=$?
}
checksum() { grep -ho 'archive checksum 0x[0-9a-f]* ([0-9]* episodes)' "$work/$1.out" | tail -n 1; }

run reference
[ $rc -eq 0 ] || fail "uninterrupted run: exit $rc"
want=$(checksum reference)
[ -n "$want" ] || fail "no checksum from the uninterrupted run"
grep -q 'controlled stop: quick stop to joints 1-7, all stood still' "$work/reference.err" ||
  fail "the completed run did not end in a controlled stop"

for sig in TERM INT HUP; do
  case $sig in TERM) code=143 ;; INT) code=130 ;; HUP) code=129 ;; esac
  name=$(echo "$sig" | tr 'A-Z' 'a-z')
  before=$(grep -c 'after its quick stop began; switch on disabled' "$work/serve.log" || true)
  "$controller" --bus "$bus" --seed $seed --episodes "$episodes" --out "$work/$name" \
    --print-checksum --progress-every 0.1 > "$work/$name.out" 2> "$work/$name.err" &
  ctl_pid=$!
  for _ in $(seq 1 600); do
    grep -q ' episodes, ratio' "$work/$name.err" 2>/dev/null && break
    sleep 0.01
  done
  sleep "0.$((RANDOM % 3))$((RANDOM % 10))"
  kill -"$sig" "$ctl_pid"
  rc=0; wait "$ctl_pid" || rc=$?
  ctl_pid=""
  [ $rc -eq $code ] || fail "SIG$sig: exit $rc, want $code"
  grep -q "stopped by SIG$sig after [0-9]* whole episodes (journal in --out): resume with --resume" \
    "$work/$name.err" || fail "SIG$sig: no 'stopped by SIG$sig ... resume with --resume' line"
  grep -q 'controlled stop: quick stop to joints 1-7, all stood still after' "$work/$name.err" ||
    fail "SIG$sig: the controller did not report a complete controlled stop"
  for _ in $(seq 1 100); do
    after=$(grep -c 'after its quick stop began; switch on disabled' "$work/serve.log" || true)
    [ $((after - before)) -ge 7 ] && break
    sleep 0.02
  done
  [ $((after - before)) -ge 7 ] ||
    fail "SIG$sig: the serve logged $((after - before)) joints standing still in switch on disabled, want 7"
  kept=$(grep -o 'after [0-9]* whole episodes' "$work/$name.err" | grep -o '[0-9]*')
  run "$name" --resume
  [ $rc -eq 0 ] || fail "SIG$sig: the resumed run: exit $rc"
  got=$(checksum "$name")
  [ "$got" = "$want" ] || fail "SIG$sig then --resume: $got, uninterrupted $want"
  echo "SIG$sig: exit $code after $kept whole episodes, controlled stop ($(grep -o 'all stood still after [0-9.]* s' "$work/$name.err")), resumed to $got"
done
kill -INT "$serve_pid"; wait "$serve_pid" 2>/dev/null || true; serve_pid=""
echo "stop_signals: SIGTERM, SIGINT, SIGHUP each end in a controlled stop and resume to $want"
