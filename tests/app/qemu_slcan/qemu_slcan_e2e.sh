#!/usr/bin/env bash
# End to end over a real CAN link out of QEMU (docs/can.md, "SLCAN"): the Cortex-M7 controller
# image (firmware.app.slcan_controller, QEMU mps2-an500) speaks SLCAN on UART0 → QEMU's chardev
# socket → curio-can slcan-bridge → the UDP bus → curio-sim serve (ODE arm). In parallel
# curio-controller runs the same exploration on the host against its own curio-sim serve; the
# two archive checksums must be equal.
#   qemu_slcan_e2e.sh IMAGE CURIO_SIM CURIO_CAN CURIO_CONTROLLER WORKDIR [ALGO] [EPISODES] [SEED]
#                     [BOOTSTRAP]
# ALGO: MGE-EFR (default), RGE-EFR, RPE or MGE-bVAE (the int8 β-VAE encoder runs in the
# image); EPISODES after the bootstrap (default 400: 100 + 400); BOOTSTRAP default: the
# algorithm's (100 EFR, 400 learned).
# Exit 77 (ctest: skipped) when the image has not been cross-built (cmake --preset cortex-m7
# && cmake --build --preset cortex-m7; toolchain/test.sh does) or qemu-system-arm is missing.
set -euo pipefail
image=$1 sim=$2 can=$3 controller=$4 work=$5 algo=${6:-MGE-EFR} episodes=${7:-400} seed=${8:-0}
bootstrap=${9:-}
image_args="arg=algo=$algo,arg=seed=$seed,arg=episodes=$episodes"
host_args=()
if [ -n "$bootstrap" ]; then
  image_args="$image_args,arg=bootstrap=$bootstrap"
  host_args=(--bootstrap "$bootstrap")
fi
if [ ! -f "$image" ]; then
  echo "SKIP: no Cortex-M7 image at $image (build it: cmake --preset cortex-m7 && cmake --build --preset cortex-m7)"
  exit 77
fi
command -v qemu-system-arm >/dev/null || { echo "SKIP: qemu-system-arm not installed"; exit 77; }
rm -rf "$work" && mkdir -p "$work"

# Two port pairs of our own (QEMU's bus, the host run's bus): from the PID, skipping taken ones.
port=$(/usr/bin/python3 "$(dirname "$0")/../../common/free_udp_ports.py" 4 $$)
[ -n "$port" ] || { echo "no free UDP ports on 127.0.0.1"; exit 1; }
qemu_bus="udp:127.0.0.1:$port?ports=2"
host_bus="udp:127.0.0.1:$((port + 2))?ports=2"
pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; }
trap cleanup EXIT

start=$(date +%s.%N)
"$sim" serve --bus "$qemu_bus" --physics ode --seed "$seed" --exit-after-idle 30 --status-every 0 \
  2> "$work/serve_qemu.log" &
pids+=($!)
"$sim" serve --bus "$host_bus" --physics ode --seed "$seed" --exit-after-idle 30 --status-every 0 \
  2> "$work/serve_host.log" &
pids+=($!)

# The host's run, in parallel.
"$controller" --bus "$host_bus" --algo "$algo" --seed "$seed" --episodes "$episodes" \
  "${host_args[@]}" --out "$work/host" --quiet --print-checksum > "$work/host.out" 2> "$work/host.err" &
host_pid=$!
pids+=($host_pid)

# QEMU waits for the bridge to connect (wait=on) before the image starts.
sock="$work/uart.sock"
qemu-system-arm -M mps2-an500 -nographic -monitor none \
  -semihosting-config "enable=on,target=native,$image_args" \
  -serial "unix:$sock,server=on,wait=on" -kernel "$image" > "$work/qemu.log" 2>&1 &
qemu_pid=$!
pids+=($qemu_pid)
"$can" slcan-bridge --serial "unix:$sock" --bus "$qemu_bus" --fd 2> "$work/bridge.log" &
pids+=($!)

qemu_rc=0
wait $qemu_pid || qemu_rc=$?
qemu_end=$(date +%s.%N)
host_rc=0
wait $host_pid || host_rc=$?
sleep 0.2
cat "$work/qemu.log"
cat "$work/bridge.log"
cat "$work/host.out"
[ "$qemu_rc" = 0 ] || { echo "FAIL: the image exited $qemu_rc"; cat "$work/serve_qemu.log"; exit 1; }
[ "$host_rc" = 0 ] || { echo "FAIL: curio-controller exited $host_rc"; cat "$work/host.err"; exit 1; }
image_sum=$(grep -o 'archive checksum 0x[0-9a-f]*' "$work/qemu.log" | awk '{print $3}')
host_sum=$(grep -o 'archive checksum 0x[0-9a-f]*' "$work/host.out" | awk '{print $3}')
image_n=$(grep -o 'archive checksum 0x[0-9a-f]* ([0-9]* episodes)' "$work/qemu.log" | grep -o '([0-9]*' | tr -d '(')
qemu_s=$(echo "$qemu_end - $start" | bc)
echo "QEMU image over SLCAN: $image_n episodes in ${qemu_s} s wall; archive checksum image $image_sum, host $host_sum"
[ -n "$image_sum" ] && [ "$image_sum" = "$host_sum" ] || { echo "FAIL: archive checksums differ"; exit 1; }
echo "PASS: $algo seed $seed, the image's archive equals curio-controller's bit for bit"
