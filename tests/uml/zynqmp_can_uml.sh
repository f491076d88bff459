#!/usr/bin/env bash
# The ZynqMP controller image on a kernel CAN bus: inside User-mode Linux, curio-sim serve on
# the classic vcan interface (vcan_classic, MTU 16) and the image in QEMU's xlnx-zcu102, whose
# CAN0 (driven by hal/zynqmp/zynqmp_can.cpp, register level, interrupt driven) joins the same
# interface through QEMU's can-host-socketcan. In parallel curio-controller runs the same
# exploration on the host (classic UDP bus, its own serve); the two archive checksums must be
# equal.
#
#   zynqmp_can_uml.sh IMAGE CURIO_SIM CURIO_CONTROLLER WORKDIR [ALGO] [EPISODES] [SEED]
#                     [BOOTSTRAP]
#
#   QEMU xlnx-zcu102: CAN0 ─ QEMU can-bus ─ can-host-socketcan ─ vcan_classic (UML kernel)
#     ─ curio-sim serve --bus socketcan:vcan_classic --physics ode --seed SEED
#
# ALGO default MGE-EFR, EPISODES default 20 (after the bootstrap), SEED 0, BOOTSTRAP the
# algorithm's default (100 EFR). Prints the image's log (time per episode, frames/s, the
# driver's counters, `archive checksum 0x…`) and the kernel's frame counts. WORKDIR (emptied)
# keeps qemu.log, serve.log, candump.log, vcan_stats.txt, host.out. Environment:
# ZYNQMP_CAN_UML_TIMEOUT (s, 1800), ZYNQMP_CAN_UML_CANDUMP (1/0, default 0),
# ZYNQMP_CAN_UML_SCHED (--no-batch: UML's command under SCHED_OTHER; the default for MGE-bVAE),
# ZYNQMP_CAN_UML_FAULT: a fault injected inside UML while the image runs, and what must follow
# (the same faults tests/app/bus_faults.sh tries on the Linux controller):
#   restart:AFTER:DELAY  serve killed AFTER s into the run, a new one DELAY s later: the image
#                        recovers, reports the fault and the 8 node reboots and a replay, and
#                        its checksum still equals the host's undisturbed run
#   second_serve         two serves (two arms) on the bus: the image refuses to explore and
#                        names the fault duplicate_node; no checksum
#   flood:RATE           RATE foreign frames/s on the bus: counted as foreign, checksum equal
#   master:AFTER         a second master's SYNC AFTER s into the run (it would step the arm
#                        under our episode): the image stops and names the fault other_master
# Exit 0: the image passed (or failed as the fault requires) and its checksum equals the
# host's; 1: failure; 77 (skipped): no image, no qemu-system-aarch64, no UML, or UML cannot
# boot here.
set -euo pipefail
if [ $# -lt 4 ]; then
  sed -n '2,25p' "$0" >&2
  exit 2
fi
image=$1 sim=$2 controller=$3 work=$4 algo=${5:-MGE-EFR} episodes=${6:-20} seed=${7:-0}
bootstrap=${8:-}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
if [ ! -f "$image" ]; then
  echo "SKIP: no ZynqMP image at $image (cmake --preset zynqmp && cmake --build --preset zynqmp)"
  exit 77
fi
command -v qemu-system-aarch64 > /dev/null || { echo "SKIP: qemu-system-aarch64 not installed"; exit 77; }
command -v linux.uml > /dev/null || { echo "SKIP: user-mode-linux not installed"; exit 77; }
[ -x "$sim" ] || { echo "FAIL: no curio-sim at $sim"; exit 1; }
[ -x "$controller" ] || { echo "FAIL: no curio-controller at $controller"; exit 1; }
rm -rf "$work" && mkdir -p "$work"
work=$(cd "$work" && pwd)
sim=$(cd "$(dirname "$sim")" && pwd)/$(basename "$sim")
image=$(cd "$(dirname "$image")" && pwd)/$(basename "$image")
image_args=("algo=$algo" "seed=$seed" "episodes=$episodes" "progress=0")
host_args=()
if [ -n "$bootstrap" ]; then
  image_args+=("bootstrap=$bootstrap")
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
  ${host_args[@]+"${host_args[@]}"} --out "$work/host" --quiet --print-checksum > "$work/host.out" 2> "$work/host.err" &
host_pid=$!
trap 'kill $serve_pid $host_pid 2>/dev/null || true' EXIT

# QEMU's start-up inside UML: its four 64 MiB flash fills cost ~80 s of page faults there;
# qemu_flash_fill.c maps a file of 0xFF bytes instead (without a C compiler: the slow way).
if cc -O2 -shared -fPIC -o "$work/qemu_flash_fill.so" "$here/qemu_flash_fill.c" -ldl \
     2> "$work/shim-build.log"; then
  head -c 67108864 /dev/zero | tr '\0' '\377' > "$work/ff.bin"
fi

# MGE-bVAE's camera image arrives as a 1,757-frame burst: without wakeup preemption
# (run-in-uml.sh's default SCHED_BATCH) QEMU's SocketCAN reader fills the model's 64-frame RX
# FIFO before the vCPU runs its interrupt, so those runs keep SCHED_OTHER.
sched=${ZYNQMP_CAN_UML_SCHED:-}
if [ -z "$sched" ] && [ "$algo" = MGE-bVAE ]; then sched=--no-batch; fi
fault=${ZYNQMP_CAN_UML_FAULT:-}
export CURIO_ZYNQMP_FAULT=$fault
rc=0
"$here/run-in-uml.sh" ${sched:+"$sched"} --rw "$work" --timeout "${ZYNQMP_CAN_UML_TIMEOUT:-1800}" -- \
  "$here/zynqmp_can_uml_inside.sh" "$sim" "$image" "$work" "$seed" "${ZYNQMP_CAN_UML_CANDUMP:-0}" \
  "${image_args[@]}" || rc=$?
rm -f "$work/ff.bin"
cat "$work/qemu.log" 2> /dev/null || true
if [ "$rc" = 125 ]; then echo "SKIP: UML cannot boot on this host"; exit 77; fi
host_rc=0
wait $host_pid || host_rc=$?
grep -E 'RX:|TX:' -A1 "$work/vcan_stats.txt" 2> /dev/null | sed 's/^/  vcan_classic /' || true
if [ -f "$work/qemu_wall.txt" ]; then
  read -r t0 t1 < "$work/qemu_wall.txt"
  echo "  QEMU wall time inside UML: $(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }') s (start-up and the arm's bring-up included)"
fi
[ -f "$work/fault.log" ] && sed 's/^/  fault: /' "$work/fault.log"
if [ "$fault" = second_serve ]; then
  [ "$rc" != 0 ] || { echo "FAIL: the image explored beside two arms"; exit 1; }
  grep -q 'duplicate_node' "$work/qemu.log" || { echo "FAIL: the image did not name the fault duplicate_node"; exit 1; }
  echo "PASS: two arms on the bus: the image refused ($(grep -o 'start_arm: .*' "$work/qemu.log"))"
  exit 0
fi
if [ "${fault%%:*}" = master ]; then
  [ "$rc" != 0 ] || { echo "FAIL: the image explored on under a second master"; exit 1; }
  grep -q 'other_master' "$work/qemu.log" || { echo "FAIL: the image did not name the fault other_master"; exit 1; }
  echo "PASS: a second master's SYNC: the image stopped ($(grep -o 'last episode [^,]*' "$work/qemu.log"); $(grep -o 'other-master frames [0-9]*' "$work/qemu.log"))"
  exit 0
fi
[ "$rc" = 0 ] || { echo "FAIL: the image exited $rc"; tail -n 5 "$work/qemu.err" "$work/serve.log"; exit 1; }
case $fault in
  restart:*)
    grep -q 'node reboots 8,' "$work/qemu.log" || { echo "FAIL: the image did not report the 8 node reboots"; exit 1; }
    grep -Eq 'replays [1-9]' "$work/qemu.log" || { echo "FAIL: the image reported no replay"; exit 1; }
    ;;
  flood:*)
    grep -Eq 'foreign [0-9]+/[0-9]+/[1-9]' "$work/qemu.log" || { echo "FAIL: the image counted no foreign frame"; exit 1; }
    ;;
esac
[ "$host_rc" = 0 ] || { echo "FAIL: curio-controller exited $host_rc"; cat "$work/host.err"; exit 1; }
image_sum=$(grep -o 'archive checksum 0x[0-9a-f]*' "$work/qemu.log" | awk '{print $3}')
host_sum=$(grep -o 'archive checksum 0x[0-9a-f]*' "$work/host.out" | awk '{print $3}')
echo "archive checksum: image through its CAN controller and the kernel $image_sum, host $host_sum"
[ -n "$image_sum" ] && [ "$image_sum" = "$host_sum" ] || { echo "FAIL: archive checksums differ"; exit 1; }
echo "PASS: $algo seed $seed, the ZynqMP image's archive through SocketCAN equals curio-controller's bit for bit"
