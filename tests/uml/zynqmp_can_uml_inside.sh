#!/bin/bash
# The UML half of tests/uml/zynqmp_can_uml.sh (runs inside tests/uml/run-in-uml.sh, as root):
# curio-sim serve on the classic vcan interface, and the ZynqMP controller image in QEMU with
# its CAN bus bridged to the same interface by can-host-socketcan: the image's CAN0 and the
# serve meet on the kernel's SocketCAN, as a board and a Linux PC on one CAN bus.
#   zynqmp_can_uml_inside.sh CURIO_SIM IMAGE WORKDIR SEED CANDUMP(0|1) IMAGE_ARG...
# Logs in WORKDIR: qemu.log (the image's UART0 console), qemu.err, serve.log, candump.log,
# vcan_stats.txt. Exit: QEMU's (the image's status).
set -u
sim=$1 image=$2 work=$3 seed=$4 candump=$5
shift 5
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
iface=vcan_classic
pids=()
if [ "$candump" = 1 ]; then
  candump -L "$iface" > "$work/candump.log" 2>&1 &
  pids+=($!)
fi
"$sim" serve --bus "socketcan:$iface" --physics ode --seed "$seed" --exit-after-idle 900 \
  --status-every 0 2> "$work/serve.log" &
serve_pid=$!
sleep 0.5
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
echo "$start $end" > "$work/qemu_wall.txt"
kill -TERM "$serve_pid" 2> /dev/null
wait "$serve_pid" 2> /dev/null
ip -s -d link show "$iface" > "$work/vcan_stats.txt" 2>&1
for p in "${pids[@]}"; do kill -INT "$p" 2> /dev/null; wait "$p" 2> /dev/null; done
exit "$rc"
