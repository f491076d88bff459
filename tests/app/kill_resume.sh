#!/usr/bin/env bash
# Nothing lost: `curio-sim serve` and `curio-controller` as processes on the UDP bus
# (kinematic, MGE-EFR); the controller, the serve, or both are SIGKILLed at random points of the
# run and the run is resumed with `curio-controller --resume` each time. The final archive
# checksum and the result files must be bit-identical to an uninterrupted run with the same
# seed, and every resume must continue at the first episode the journal does not hold (so at
# most the episode in flight is run again).
#   kill_resume.sh CURIO_SIM CURIO_CONTROLLER WORKDIR KILLS EPISODES [RANDOM_SEED]
set -euo pipefail
sim=$1 controller=$2 work=$3 kills=$4 episodes=$5
RANDOM=${6:-$$}
seed=3
rm -rf "$work" && mkdir -p "$work"
port=$(/usr/bin/python3 "$(dirname "$0")/../common/free_udp_ports.py" 2 $$)
[ -n "$port" ] || { echo "no free UDP port pair on 127.0.0.1"; exit 1; }
bus="udp:127.0.0.1:$port?ports=2"
serve_pid="" ctl_pid=""
trap 'for p in $serve_pid $ctl_pid; do kill -9 "$p" 2>/dev/null || true; done' EXIT
fail() { echo "FAIL: $*"; for f in "$work"/*.err "$work"/*.log; do echo "== $f"; tail -n 4 "$f"; done; exit 1; }

n_serve=0
serve() {
  n_serve=$((n_serve + 1))
  "$sim" serve --bus "$bus" --physics kinematic --seed $seed --exit-after-idle 60 \
    --status-every 0 2> "$work/serve$n_serve.log" &
  serve_pid=$!
}
stop_serve() { kill -INT "$serve_pid" 2>/dev/null || true; wait "$serve_pid" 2>/dev/null || true; serve_pid=""; }
n_ctl=0
controller() {  # controller DIR [--resume]: in the background, PID in $ctl_pid
  n_ctl=$((n_ctl + 1))
  "$controller" --bus "$bus" --seed $seed --episodes "$episodes" --out "$1" --print-checksum \
    --hold-time 20 --progress-every 0.5 "${@:2}" > "$work/ctl$n_ctl.out" 2> "$work/ctl$n_ctl.err" &
  ctl_pid=$!
}
checksum() { grep -ho 'archive checksum 0x[0-9a-f]* ([0-9]* episodes)' "$@" | tail -n 1; }
# Episodes journaled in DIR, as the controller's scan reads them (it refuses to start on a used
# --out without --resume and says what the journal holds; nothing is changed).
journaled() {
  local msg
  msg=$("$controller" --bus loopback --seed $seed --episodes "$episodes" --out "$1" --quiet 2>&1 || true)
  echo "$msg" | grep -o '[0-9]* episodes journaled' | grep -o '^[0-9]*' || echo 0
}
records() {  # whole 64-byte slots in DIR's journal file (header 128 B)
  local s
  s=$(stat -c %s "$1/journal.bin" 2>/dev/null || echo 0)
  [ "$s" -gt 128 ] && echo $(((s - 128) / 64)) || echo 0
}

# The uninterrupted run.
t0=$(date +%s.%N)
serve
controller "$work/ref"
wait "$ctl_pid" || fail "uninterrupted run: exit $?"
ctl_pid=""
stop_serve
want=$(checksum "$work/ctl1.out")
[ -n "$want" ] || fail "no checksum from the uninterrupted run"
total=$(echo "$want" | grep -o '([0-9]*' | tr -d '(')

# The interrupted run.
run="$work/run"
serve
controller "$run"
redone=0 resumes=0 kinds="" serve_kills=0
for k in $(seq 1 "$kills"); do
  # A random point: after 3..(3 + total/(kills+1)) more journaled records, then 0..9 ms more.
  start=$(records "$run")
  want_more=$((3 + RANDOM % (total / (kills + 1) + 1)))
  for _ in $(seq 1 2000); do
    [ "$(records "$run")" -ge $((start + want_more)) ] && break
    kill -0 "$ctl_pid" 2>/dev/null || break
    sleep 0.005
  done
  kill -0 "$ctl_pid" 2>/dev/null || { echo "run finished before kill $k"; break; }
  sleep "0.00$((RANDOM % 10))"
  case $((RANDOM % 4)) in
    0 | 1) victim=controller ;;
    2) victim=serve ;;
    *) victim=both ;;
  esac
  kinds="$kinds $victim"
  if [ $victim = serve ]; then
    serve_kills=$((serve_kills + 1))
    kill -9 "$serve_pid"; wait "$serve_pid" 2>/dev/null || true
    sleep "0.$((RANDOM % 5))"
    serve  # the controller holds the arm (--hold-time) and goes on
    continue
  fi
  kill -9 "$ctl_pid"; wait "$ctl_pid" 2>/dev/null || true
  if [ $victim = both ]; then kill -9 "$serve_pid"; wait "$serve_pid" 2>/dev/null || true; serve; fi
  at_kill=$(journaled "$run")
  controller "$run" --resume
  resumes=$((resumes + 1))
  for _ in $(seq 1 400); do
    grep -q 'continuing at episode' "$work/ctl$n_ctl.err" 2>/dev/null && break
    kill -0 "$ctl_pid" 2>/dev/null || break
    sleep 0.01
  done
  cont=$(grep -o 'continuing at episode [0-9]*' "$work/ctl$n_ctl.err" | grep -o '[0-9]*$' || true)
  [ -n "$cont" ] || fail "resume $resumes printed no 'continuing at episode'"
  # Everything journaled is kept; the one episode in flight at the kill is run again.
  [ "$cont" -eq "$at_kill" ] || fail "kill $k: journal held $at_kill episodes, resume continued at $cont"
  redone=$((redone + 1))
done
rc=0; wait "$ctl_pid" || rc=$?
ctl_pid=""
[ $rc -eq 0 ] || fail "the resumed run: exit $rc"
stop_serve
got=$(checksum "$work"/ctl"$n_ctl".out)
[ "$got" = "$want" ] || fail "interrupted run: $got, uninterrupted $want"
# The result files, byte for byte (summary.json also holds wall time and the bus counters and
# their note, which differ with the kills and with load: compared without those; after a resume
# they cover the last process only).
for f in $(cd "$work/ref" && find runs plots_data -type f ! -name "*.gp" | sort) summary.csv controllability.csv; do
  cmp -s "$work/ref/$f" "$run/$f" || fail "$f differs from the uninterrupted run's"
done
strip() { /usr/bin/python3 -c 'import json,sys
d=json.load(open(sys.argv[1]))
def drop(x):
  if isinstance(x, dict):
    return {k: drop(v) for k, v in x.items() if k not in ("seconds", "wall_seconds", "seconds_per_run", "cpu_seconds", "bus")}
  if isinstance(x, list):
    return [drop(v) for v in x if not (isinstance(v, str) and v.startswith("Over the bus:"))]
  return x
print(json.dumps(drop(d), sort_keys=True))' "$1"; }
[ "$(strip "$work/ref/summary.json")" = "$(strip "$run/summary.json")" ] ||
  fail "summary.json differs (beyond time and bus counters)"
# What the bus did is summed over every controller process of the run (bus_counters.json): a
# serve killed under a running controller reboots all 8 nodes, and those reboots stay in the
# summary even when that controller is killed later.
bus=$(/usr/bin/python3 -c 'import json,sys
b=json.load(open(sys.argv[1]))["bus"]
print(b["controller_processes"], b["node_reboots"])' "$run/summary.json")
[ "${bus% *}" -eq $((resumes + 1)) ] ||
  fail "summary.json counts ${bus% *} controller processes, the run had $((resumes + 1))"
[ "${bus#* }" -ge $((8 * serve_kills)) ] ||
  fail "summary.json holds ${bus#* } node reboots; $serve_kills serve kills under a running controller make >= $((8 * serve_kills))"
t1=$(date +%s.%N)
echo "kill_resume: $kills kills ($kinds), $resumes resumes, $total episodes: $got identical to" \
  "the uninterrupted run; runs/, plots_data/, summary.csv, controllability.csv identical; summary.json identical but for" \
  "time and bus counters; episodes redone: $redone (one per controller kill, the one in flight)" \
  "in $(/usr/bin/python3 -c "print(round($t1 - $t0, 1))") s; bus over all processes: ${bus% *} processes, ${bus#* } node reboots"
