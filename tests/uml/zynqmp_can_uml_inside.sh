#!/bin/bash
# The UML half of tests/uml/zynqmp_can_uml.sh (runs inside tests/uml/run-in-uml.sh, as root):
# curio-sim serve on the classic vcan interface, and the ZynqMP controller image in QEMU with
# its CAN bus bridged to the same interface by can-host-socketcan: the image's CAN0 and the
# serve meet on the kernel's SocketCAN, as a board and a Linux PC on one CAN bus.
#   zynqmp_can_uml_inside.sh CURIO_SIM IMAGE WORKDIR SEED CANDUMP(0|1) IMAGE_ARG...
# Logs in WORKDIR: qemu.log (the image's UART0 console), qemu.err, serve.log, candump.log,
# vcan_stats.txt. Exit: QEMU's (the image's status).
# CURIO_ZYNQMP_FAULT (optional) injects a fault while the image runs:
#   restart:AFTER:DELAY  AFTER s into the exploration the serve is killed (SIGKILL) and a new
#                        one starts DELAY s later (serve2.log)
#   second_serve         a second serve is on the bus before the image starts (serve2.log)
#   flood:RATE           from the start of the exploration, cangen puts RATE foreign frames/s
#                        (id 0x7A0, 8 bytes) on the bus until the image ends
#   master:AFTER         AFTER s into the exploration a second master sends one SYNC (0x080)
set -u
sim=$1 image=$2 work=$3 seed=$4 candump=$5
shift 5
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
iface=vcan_classic
pids=()
candump_pid=
if [ "$candump" = 1 ]; then
  candump -L "$iface" > "$work/candump.log" 2>&1 &
  candump_pid=$!
fi
# QEMU's SocketCAN reader takes the kernel's default receive buffer (212,992 bytes, ≈ 200
# classic frames at ~1 KB of kernel memory each): a camera image's 1,757-frame ISO-TP burst
# from the serve overflows it while QEMU is busy, and the kernel drops the rest. A bench PC
# gives its CAN sockets room too; here 16 MiB (UML's own kernel, nothing outside it).
echo 16777216 > /proc/sys/net/core/rmem_default
echo 16777216 > /proc/sys/net/core/rmem_max
fault=${CURIO_ZYNQMP_FAULT:-}
serve() {  # serve LOG: one serve on the interface, its pid in $serve_pid
  "$sim" serve --bus "socketcan:$iface" --physics ode --seed "$seed" --exit-after-idle 900 \
    --status-every 0 2> "$1" &
  serve_pid=$!
  pids+=("$serve_pid")
}
serve "$work/serve.log"
first_serve=$serve_pid
if [ "$fault" = second_serve ]; then serve "$work/serve2.log"; fi
sleep 0.5
if [ -n "$fault" ] && [ "$fault" != second_serve ]; then
  (  # the injector: waits until the image explores, then acts
    for _ in $(seq 1 3000); do grep -q 'arm physics' "$work/qemu.log" 2> /dev/null && break; sleep 0.1; done
    case $fault in
      restart:*)
        IFS=: read -r _ after delay <<< "$fault"
        sleep "$after"
        kill -9 "$first_serve"
        echo "serve killed at $(date +%s.%N)" > "$work/fault.log"
        sleep "$delay"
        "$sim" serve --bus "socketcan:$iface" --physics ode --seed "$seed" --exit-after-idle 60 \
          --status-every 0 2> "$work/serve2.log" &
        echo "serve restarted at $(date +%s.%N)" >> "$work/fault.log"
        wait
        ;;
      master:*)
        sleep "${fault#master:}"
        cansend "$iface" 080#
        echo "a second master's SYNC at $(date +%s.%N)" > "$work/fault.log"
        ;;
      flood:*)
        rate=${fault#flood:}
        gap=$(awk -v r="$rate" 'BEGIN { printf "%.3f", 1000 / r }')
        echo "flood: $rate frames/s (cangen -g $gap ms)" > "$work/fault.log"
        exec cangen "$iface" -g "$gap" -I 7A0 -L 8 -D i
        ;;
    esac
  ) &
  injector=$!
fi
preload=()
if [ -f "$work/qemu_flash_fill.so" ] && [ -f "$work/ff.bin" ]; then
  preload=(env "LD_PRELOAD=$work/qemu_flash_fill.so" "CURIO_FF_FILE=$work/ff.bin")
fi
start=$(date +%s.%N)
ZCU102_SERIAL=stdio ZCU102_QEMU="-object can-host-socketcan,id=host0,if=$iface,canbus=curiocan" \
  ${preload[@]+"${preload[@]}"} "$here/../../toolchain/boards/zcu102/run-zcu102.sh" "$image" "$@" \
  > "$work/qemu.log" 2> "$work/qemu.err" < /dev/null
rc=$?
end=$(date +%s.%N)
if [ -n "${injector:-}" ]; then
  pkill -P "$injector" 2> /dev/null  # its serve or cangen (children of our own injector)
  kill "$injector" 2> /dev/null
  wait "$injector" 2> /dev/null
fi
echo "$start $end" > "$work/qemu_wall.txt"
for p in "${pids[@]}"; do kill -TERM "$p" 2> /dev/null; wait "$p" 2> /dev/null; done
ip -s -d link show "$iface" > "$work/vcan_stats.txt" 2>&1
if [ -n "$candump_pid" ]; then kill -INT "$candump_pid" 2> /dev/null; wait "$candump_pid" 2> /dev/null; fi
exit "$rc"
