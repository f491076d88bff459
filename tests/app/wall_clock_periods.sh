#!/usr/bin/env bash
# curio-controller --period-us against `curio-sim serve` over UDP: the periods run on the wall
# clock (40 episodes × 50 periods of 2 ms: at least 4 s), the results are curio-lab's bit for
# bit (pacing changes when, never what), and summary.json "control_periods" and
# control_periods.csv count every period. The serve, told the same period (--period-us), sees
# SYNC intervals of about 2 ms. An impossible --cpu is refused with its reason.
#   wall_clock_periods.sh CURIO_SIM CURIO_CONTROLLER CURIO_LAB WORKDIR
set -euo pipefail
sim=$1 controller=$2 lab=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
port=$(/usr/bin/python3 "$(dirname "$0")/../common/free_udp_ports.py" 2 $$)
[ -n "$port" ] || { echo "no free UDP port pair on 127.0.0.1"; exit 1; }
bus="udp:127.0.0.1:$port?ports=2"
"$sim" serve --bus "$bus" --seed 3 --exit-after-idle 20 --status-every 0 --period-us 2000 \
  2> "$work/serve.log" &
serve_pid=$!
trap 'kill $serve_pid 2>/dev/null || true' EXIT
start=$(date +%s.%N)
"$controller" --bus "$bus" --algo MGE-EFR --seed 3 --bootstrap 20 --episodes 20 --period-us 2000 \
  --out "$work/controller" --quiet > "$work/controller.out" 2> "$work/controller.err" ||
  { cat "$work/controller.err" "$work/serve.log"; exit 1; }
elapsed=$(python3 -c "import time; print(time.time() - $start)")
"$lab" run --replace --algos MGE-EFR --seeds 3 --bootstrap 20 --episodes 20 --out "$work/lab" --quiet \
  > /dev/null 2> "$work/lab.err"
cat "$work/controller.out"
for f in runs/MGE-EFR_sigma0.05_seed3.csv runs/MGE-EFR_sigma0.05_seed3_interest.csv; do
  cmp "$work/lab/$f" "$work/controller/$f" || { echo "paced run differs from curio-lab: $f"; exit 1; }
done
python3 - "$work/controller/summary.json" "$work/controller/control_periods.csv" "$elapsed" <<'PY'
import csv, json, sys
p = json.load(open(sys.argv[1]))["control_periods"]
rows = list(csv.DictReader(open(sys.argv[2])))
# Replayed attempts add periods; never fewer than 40 episodes × 50.
assert p["period_us"] == 2000 and p["periods"] >= 2000 and len(rows) == p["periods"], (p, len(rows))
assert 0 <= p["lateness_us"]["p50"] <= p["lateness_us"]["p99"] <= p["lateness_us"]["max"], p
assert 0 < p["work_us"]["p50"] <= p["work_us"]["max"] and p["overruns"] >= 0, p
assert float(sys.argv[3]) >= 40 * 49 * 0.002, f"{sys.argv[3]} s is less than the periods' wall time"
print(f"{p['periods']} periods of 2 ms: woke late p99 {p['lateness_us']['p99']:.0f} us, {p['overruns']} overruns")
PY
set +e
"$controller" --bus "$bus" --cpu 4000 --episodes 5 --out "$work/cpu" --quiet 2> "$work/cpu.err"; code=$?
set -e
[ "$code" = 1 ] && grep -q "^curio-controller: --cpu 4000: cannot run on that CPU" "$work/cpu.err" ||
  { echo "--cpu 4000: exit $code: $(cat "$work/cpu.err")"; exit 1; }
kill -INT $serve_pid; wait $serve_pid || true
# 40 episodes × 49 intervals at least (replays add more); the median within 0.5 ms of 2 ms.
line=$(grep "SYNC intervals in episodes against the 2000 us period" "$work/serve.log") ||
  { echo "the serve printed no SYNC timing"; cat "$work/serve.log"; exit 1; }
echo "$line"
python3 - "$line" <<'PY'
import re, sys
m = re.search(r"(\d+) intervals, p50 (\d+) / p99 (\d+) / max (\d+) us", sys.argv[1])
n, p50 = int(m.group(1)), int(m.group(2))
assert n >= 40 * 49 and 1500 <= p50 <= 2500, (n, p50)
PY
echo "wall-clock periods over $bus: results identical to curio-lab's"
