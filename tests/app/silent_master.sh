#!/usr/bin/env bash
# The drives watch the controller (`curio-sim serve` as a process, on the UDP bus): a fake
# master made of `curio-can send` calls configures the joints as Curio's controller does
# (heartbeat consumer 0x1016.1 = 127 << 16 | 200 ms, 0x6007 = 3 quick stop, 0x605A = 2,
# 0x6085 = 1000 rad/s²), enables them, moves every joint at 20 rad/s with its heartbeat (0x77F)
# and SYNCs, then goes silent, as a killed controller does. Every joint holds its last target
# (no SYNC, no new target), must send EMCY 0x8130 after the consumer time, quick-stop on its
# own clock (at rest already: one period) and end in switch on disabled where it stood; the
# serve logs each miss and standstill. Prints the times from the last heartbeat to the last
# EMCY and from each miss to the standstill.
#   silent_master.sh CURIO_SIM CURIO_CAN WORKDIR [PHYSICS]
set -euo pipefail
[ -n "${SILENT_MASTER_TRACE:-}" ] && { PS4='+ $(date +%s.%N) '; set -x; }
sim=$1 can=$2 work=$3 physics=${4:-ode}
rm -rf "$work" && mkdir -p "$work"
port=$(/usr/bin/python3 "$(dirname "$0")/../common/free_udp_ports.py" 4 $$)
[ -n "$port" ] || { echo "no free UDP ports on 127.0.0.1"; exit 1; }
bus="udp:127.0.0.1:$port?ports=4"
# The frames, made before the serve starts (a loaded machine forks slowly): line 1 the
# configuration as Curio's controller writes it, NMT start, enable, episode 0 and the first
# heartbeat; lines 2-6 five control periods at 0.2 rad per period, each with the heartbeat.
/usr/bin/python3 - > "$work/frames" <<'PY'
import struct
def sdo(n, index, sub, value):
    return "%03X#%s" % (0x600 + n, struct.pack("<BHBI", 0x23, index, sub, value & 0xFFFFFFFF).hex().upper())
def rpdo(n, cw, target):
    return "%03X#%s" % (0x200 + n, struct.pack("<Hi", cw, target).hex().upper())
config = ["000#0100"]
for n in range(1, 8):
    config += [sdo(n, 0x1016, 1, (127 << 16) | 200), sdo(n, 0x6007, 0, 3), sdo(n, 0x605A, 0, 2),
               sdo(n, 0x605E, 0, 2), sdo(n, 0x6085, 0, 1000000000), sdo(n, 0x607F, 0, 314159300),
               sdo(n, 0x6060, 0, 8), sdo(n, 0x6040, 0, 6), sdo(n, 0x6040, 0, 7), sdo(n, 0x6040, 0, 15)]
config += [sdo(0x20, 0x2000, 1, 0), "77F#05"]
print(" ".join(config))
for t in range(1, 6):
    print(" ".join(["77F#05"] + [rpdo(n, 15, 200000 * t) for n in range(1, 8)] + ["080#01"]))
PY
mapfile -t lines < "$work/frames"

# One run of the fake master against a fresh serve. Its heartbeats are separate processes: on
# a loaded machine one can come more than the consumer time late, and the drives rightly stop
# early; such a run is repeated (up to 3 times), not counted as a failure.
run_once() {
  "$sim" serve --bus "$bus" --physics "$physics" --seed 4 --status-every 0 2> "$work/serve.log" &
  serve_pid=$!
  trap 'kill $serve_pid 2>/dev/null || true' EXIT
  "$can" dump --bus "$bus" -t 3000 > "$work/dump.log" &
  dump_pid=$!
  sleep 0.3
  for line in "${lines[@]}"; do
    read -ra frames <<< "$line"
    "$can" send --bus "$bus" "${frames[@]}"
    sleep 0.01
  done
  # Silence: 200 ms consumer time + one period, with room for a loaded machine.
  sleep 1
  kill -TERM $serve_pid
  status=0
  wait $serve_pid || status=$?
  trap - EXIT
  kill -INT $dump_pid 2>/dev/null || true
  wait $dump_pid || true
}
for attempt in 1 2 3; do
  run_once
  gap=$(awk '/ 77F#/ { gsub(/[()]/, "", $1); if (last != "" && $1 - last > max) max = $1 - last; last = $1 }
             END { printf "%d", max * 1000 }' "$work/dump.log")
  [ "$gap" -lt 150 ] && break
  echo "(attempt $attempt: the fake master's heartbeats were $gap ms apart on this loaded machine; again)"
done
[ "$status" = 143 ] || { echo "serve exit status $status, not 143"; cat "$work/serve.log"; exit 1; }
missed=$(grep -c 'heartbeat of node 127 missed' "$work/serve.log" || true)
still=$(grep -c 'stood still at .* after the missed heartbeat; switch on disabled' "$work/serve.log" || true)
emcy=$(grep -cE '\b08[1-7]#3081' "$work/dump.log" || true)
if [ "$missed" != 7 ] || [ "$still" != 7 ] || [ "$emcy" != 7 ]; then
  echo "expected 7 misses, 7 standstills and 7 EMCY 0x8130: $missed, $still, $emcy"
  cat "$work/serve.log"
  exit 1
fi
# Each joint stood still where its last target (1.0 rad) put it.
where=$(sed -n 's/.*stood still at \([-+0-9.]*\) rad.*/\1/p' "$work/serve.log" | sort -u)
[ "$where" = "+1.000000" ] || { echo "joints stood still at $where rad, not 1.0"; cat "$work/serve.log"; exit 1; }
# From the controller's last heartbeat to the last joint's EMCY 0x8130, as the bus saw them
# (curio-can dump's clock): the consumer time (200 ms) and the serve's wake-up.
awk '/ 77F#/ { gsub(/[()]/, "", $1); last = $1 } / 08[1-7]#3081/ { gsub(/[()]/, "", $1); emcy = $1 }
     END { printf "last heartbeat to the last EMCY 0x8130: %.1f ms\n", (emcy - last) * 1000
           if ((emcy - last) * 1000 < 200) { print "EMCY before the consumer time"; exit 1 } }' "$work/dump.log"
# ms from each joint's miss to its standstill: one period (10 ms) of the serve's clock, and its
# wake-up.
sed -n 's/.*stood still at .*, \([0-9.]*\) ms after the missed heartbeat.*/\1/p' "$work/serve.log" |
  sort -n | awk '{ a[NR] = $1 } END {
    printf "silent master (%s): 7 joints sent EMCY 0x8130 and stood still in switch on disabled; miss to standstill: p50 %.1f ms, max %.1f ms\n", "'"$physics"'", a[int((NR + 1) / 2)], a[NR]
    if (a[NR] > 250) { print "standstill later than 250 ms after the miss"; exit 1 } }'
