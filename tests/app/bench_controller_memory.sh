#!/usr/bin/env bash
# curio-controller's resident size over a long run: `curio-sim serve` and `curio-controller`
# as two processes on the userspace UDP bus (MGE-EFR, seed 0, kinematic arm, 100 + 10,300 =
# 10,400 episodes), the controller's VmRSS sampled every 0.2 s beside its progress lines.
# Prints the resident size at the start (the first sample past episode 500, after start-up)
# and at the end (the last sample before the last episode: the report's writing follows), and
# the growth per episode between them. Asserts nothing about the figures.
#   bench_controller_memory.sh CURIO_SIM CURIO_CONTROLLER WORKDIR [EPISODES]
set -euo pipefail
sim=$1 controller=$2 work=$3 episodes=${4:-10300}
rm -rf "$work" && mkdir -p "$work"
port=$(/usr/bin/python3 "$(dirname "$0")/../common/free_udp_ports.py" 2 $$)
[ -n "$port" ] || { echo "no free UDP port pair on 127.0.0.1"; exit 1; }
bus="udp:127.0.0.1:$port?ports=2"
"$sim" serve --bus "$bus" --physics kinematic --seed 0 --exit-after-idle 20 --status-every 0 \
  2> "$work/serve.log" &
serve_pid=$!
trap 'kill $serve_pid 2>/dev/null || true' EXIT
"$controller" --bus "$bus" --algo MGE-EFR --seed 0 --bootstrap 100 \
  --episodes "$episodes" --out "$work/controller" --progress-every 0.2 \
  > "$work/controller.out" 2> "$work/controller.err" &
controller_pid=$!
: > "$work/samples"
while kill -0 $controller_pid 2>/dev/null; do
  rss=$(sed -n 's/^VmRSS:[[:space:]]*\([0-9]*\) kB/\1/p' /proc/$controller_pid/status 2>/dev/null || true)
  n=$(sed -n 's/^curio-controller: \([0-9]*\)\/[0-9]* episodes.*/\1/p' "$work/controller.err" | tail -1)
  [ -n "$rss" ] && [ -n "$n" ] && echo "$n $rss" >> "$work/samples"
  sleep 0.2
done
wait $controller_pid || { cat "$work/controller.err"; exit 1; }
kill -INT $serve_pid; wait $serve_pid || true
total=$((episodes + 100))
awk -v total="$total" '
  $1 >= 500 && !start { start = 1; n0 = $1; r0 = $2 }
  $1 < total { n1 = $1; r1 = $2 }
  END {
    if (!start || n1 <= n0) { print "too few samples past episode 500"; exit 1 }
    printf "curio-controller resident size, MGE-EFR seed 0, %d episodes (kinematic, UDP bus):\n", total
    printf "  start (episode %5d): %6d kB\n  end   (episode %5d): %6d kB\n", n0, r0, n1, r1
    printf "  growth: %d kB over %d episodes (%.2f bytes/episode)\n", r1 - r0, n1 - n0, (r1 - r0) * 1024.0 / (n1 - n0)
  }' "$work/samples"
