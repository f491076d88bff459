#!/usr/bin/env bash
# End to end as documented: `curio-sim serve` and `curio-controller` as two processes on the
# userspace UDP bus; the controller's result files must equal curio-lab's for the same seed.
#   two_process_udp.sh CURIO_SIM CURIO_CONTROLLER CURIO_LAB WORKDIR [PHYSICS]
set -euo pipefail
sim=$1 controller=$2 lab=$3 work=$4 physics=${5:-ode}
rm -rf "$work" && mkdir -p "$work"
# A port range of our own: from the PID, skipping ranges something is bound to.
port=$(/usr/bin/python3 "$(dirname "$0")/../common/free_udp_ports.py" 2 $$)
[ -n "$port" ] || { echo "no free UDP port pair on 127.0.0.1"; exit 1; }
bus="udp:127.0.0.1:$port?ports=2"
"$sim" serve --bus "$bus" --physics "$physics" --seed 4 --exit-after-idle 20 --status-every 0 \
  2> "$work/serve.log" &
serve_pid=$!
trap 'kill $serve_pid 2>/dev/null || true' EXIT
"$controller" --bus "$bus" --algo MGE-EFR --seed 4 --episodes 150 --out "$work/controller" --quiet \
  > "$work/controller.out" 2> "$work/controller.err" || { cat "$work/controller.err" "$work/serve.log"; exit 1; }
"$lab" run --replace --algos MGE-EFR --seeds 4 --physics "$physics" --episodes 150 --out "$work/lab" --quiet \
  > /dev/null 2> "$work/lab.err"
kill -INT $serve_pid; wait $serve_pid || true
cat "$work/controller.out"
for f in runs/MGE-EFR_sigma0.05_seed4.csv runs/MGE-EFR_sigma0.05_seed4_interest.csv; do
  cmp "$work/lab/$f" "$work/controller/$f" || { echo "differs from curio-lab: $f"; exit 1; }
done
# 250 episodes, not counting replays: on a loaded machine a late heartbeat is a fault whose
# episode is replayed (identically: the result files above are compared bit for bit).
counts=$(sed -n 's/.* \([0-9]*\) episodes (\([0-9]*\) replayed).*/\1 \2/p' "$work/serve.log" | tail -1)
started=${counts% *} replayed=${counts#* }
[ -n "$counts" ] && [ "$((started - replayed))" = 250 ] ||
  { echo "serve did not report 250 episodes besides replays:"; cat "$work/serve.log"; exit 1; }
[ "$replayed" = 0 ] || echo "($replayed episodes replayed after faults; results unchanged)"
echo "two processes over $bus: result files identical to curio-lab's"
