#!/usr/bin/env bash
# The QEMU Cortex-M7 controller image on a kernel CAN stack, like a board with a USB-CAN
# adapter on a Linux PC: the image's UART0 (SLCAN lines, classic profile) is UML's serial
# line 1; inside UML, slcand attaches the kernel's slcan driver to it (SocketCAN interface
# slc0, classic CAN only, MTU 16) and curio-sim serve presents the arm on slc0. In parallel
# curio-controller runs the same exploration on the host (classic UDP bus, its own serve);
# the two archive checksums must be equal.
#
#   qemu_slcan_uml.sh IMAGE CURIO_SIM CURIO_CONTROLLER WORKDIR [ALGO] [EPISODES] [SEED]
#                     [BOOTSTRAP]
#
#   QEMU mps2-an500 UART0 ─chardev socket,fd=M═ relay (qemu_slcan_uml.py) ═ssl1=fd:N─ UML ttyS1
#     ─N_SLCAN (slcand)─ slc0 ─ curio-sim serve --bus socketcan:slc0 --physics ode --seed SEED
#                                 --exit-after-idle 30 --status-every 0
# The relay sends UML an empty line ('\r') after each of UML's writes: UML's serial line
# driver never calls tty_wakeup() after a write the host took at once, so slcan (which waits
# for write_wakeup after every frame) would send one frame and stall (qemu_slcan_uml.py).
#
# ALGO default MGE-EFR, EPISODES default 20 (after the bootstrap), SEED default 0, BOOTSTRAP
# default the algorithm's (100 EFR). Prints the image's log (ends with `archive checksum
# 0x…`), the serve's log, slc0's frame counts and the frame rate. WORKDIR (emptied) keeps
# qemu.log, serve.log, slcand.log, candump.log, slc0_stats.txt, uml.out/err, host.out.
# Environment: QEMU_SLCAN_UML_TIMEOUT (s, 1800), QEMU_SLCAN_UML_CANDUMP (1/0),
# QEMU_SLCAN_UML_TRACE (1: WORKDIR/line.trace, every line with its time), QEMU_SLCAN_UML_KICK
# (0: no kicks, shows the stall). Exit 0: the image passed and its checksum equals the host's;
# 1: failure; 77 (skipped): no image, no qemu-system-arm, no UML, or UML cannot boot here.
# Helpers: qemu_slcan_uml.py (launcher), qemu_slcan_uml_inside.sh (the UML side).
set -euo pipefail
if [ $# -lt 4 ]; then
  sed -n '2,29p' "$0" >&2
  exit 2
fi
image=$1 sim=$2 controller=$3 work=$4 algo=${5:-MGE-EFR} episodes=${6:-20} seed=${7:-0}
bootstrap=${8:-}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
if [ ! -f "$image" ]; then
  echo "SKIP: no Cortex-M7 image at $image (cmake --preset cortex-m7 && cmake --build --preset cortex-m7)"
  exit 77
fi
command -v qemu-system-arm > /dev/null || { echo "SKIP: qemu-system-arm not installed"; exit 77; }
command -v linux.uml > /dev/null || { echo "SKIP: user-mode-linux not installed"; exit 77; }
command -v slcand > /dev/null || { echo "SKIP: can-utils (slcand) not installed"; exit 77; }
[ -x "$sim" ] || { echo "FAIL: no curio-sim at $sim"; exit 1; }
[ -x "$controller" ] || { echo "FAIL: no curio-controller at $controller"; exit 1; }
rm -rf "$work" && mkdir -p "$work"
work=$(cd "$work" && pwd)
sim=$(cd "$(dirname "$sim")" && pwd)/$(basename "$sim")
image=$(cd "$(dirname "$image")" && pwd)/$(basename "$image")
extra="arg=can=classic"
host_args=()
if [ -n "$bootstrap" ]; then
  extra="$extra,arg=bootstrap=$bootstrap"
  host_args=(--bootstrap "$bootstrap")
fi

# The host's run, in parallel, on a classic UDP bus of its own.
port=$(/usr/bin/python3 "$here/../common/free_udp_ports.py" 2 $$)
[ -n "$port" ] || { echo "no free UDP ports on 127.0.0.1"; exit 1; }
host_bus="udp:127.0.0.1:$port?ports=2&classic=1"
"$sim" serve --bus "$host_bus" --physics ode --seed "$seed" --exit-after-idle 30 --status-every 0 \
  2> "$work/serve_host.log" &
serve_pid=$!
"$controller" --bus "$host_bus" --algo "$algo" --seed "$seed" --episodes "$episodes" \
  "${host_args[@]}" --out "$work/host" --quiet --print-checksum > "$work/host.out" 2> "$work/host.err" &
host_pid=$!
trap 'kill $serve_pid $host_pid 2>/dev/null || true' EXIT

rc=0
/usr/bin/python3 "$here/qemu_slcan_uml.py" "$image" "$sim" "$work" "$algo" "$episodes" "$seed" \
  "$extra" || rc=$?
host_rc=0
wait $host_pid || host_rc=$?
[ "$rc" = 0 ] || exit "$rc"
[ "$host_rc" = 0 ] || { echo "FAIL: curio-controller exited $host_rc"; cat "$work/host.err"; exit 1; }
image_sum=$(grep -o 'archive checksum 0x[0-9a-f]*' "$work/qemu.log" | awk '{print $3}')
host_sum=$(grep -o 'archive checksum 0x[0-9a-f]*' "$work/host.out" | awk '{print $3}')
echo "archive checksum: image over the kernel's slcan $image_sum, host $host_sum"
[ -n "$image_sum" ] && [ "$image_sum" = "$host_sum" ] || { echo "FAIL: archive checksums differ"; exit 1; }
echo "PASS: $algo seed $seed, the image's archive through the kernel equals curio-controller's bit for bit"
