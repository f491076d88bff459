#!/bin/bash
# The UML half of tests/uml/qemu_slcan_uml.sh (runs inside tests/uml/run-in-uml.sh
# --serial-fd N, as root): UML's /dev/ttyS1 is one end of a socketpair whose other end is the
# QEMU image's UART0. slcand attaches the kernel's slcan line discipline to it (slc0, classic
# CAN only), and curio-sim serve presents the arm on slc0 — a USB-CAN adapter on a bench.
#   qemu_slcan_uml_inside.sh CURIO_SIM WORKDIR SEED [CANDUMP(0|1)]
# Handshake with the host side over WORKDIR (mounted writable): writes uml_ready once slc0 is
# up and the serve runs; stops when the host writes qemu_done (or the serve exits by itself,
# --exit-after-idle 30). Logs: serve.log, slcand.log, candump.log (candump -L), slc0_stats.txt.
# Exit: 0 when the serve ran to the end (idle exit, or stopped by us); 3 if slc0 never came up.
set -u
sim=$1 work=$2 seed=$3 candump=${4:-1}
bb=$(command -v busybox)
log() { echo "uml: $*" >&2; }

m=/usr/lib/uml/modules/$(uname -r)/kernel
"$bb" insmod "$m/drivers/net/can/slcan/slcan.ko" || { log "insmod slcan failed"; exit 3; }
# The serial line's own node (UML's ttyS: char 4, minor 64 + line), independent of what the
# host's /dev holds. slcand prepends /dev/ to a name not starting with /dev/, hence the path.
"$bb" mknod /run/ttyS1 c 4 65 || { log "mknod ttyS1 failed"; exit 3; }
tty=/dev/../run/ttyS1

# slcand: C, S8 and O go out on the line (the image takes them as adapter commands), then it
# sets the N_SLCAN line discipline (the tty's speed does not matter on a socketpair) and
# renames the new netdevice to slc0. -F: stays in the foreground (we own its pid).
slcand -o -s8 -F "$tty" slc0 > "$work/slcand.log" 2>&1 &
slcand_pid=$!
for _ in $(seq 100); do
  ip link show slc0 > /dev/null 2>&1 && break
  sleep 0.1
done
if ! ip link show slc0 > /dev/null 2>&1; then
  log "slc0 did not appear"; cat "$work/slcand.log" >&2; exit 3
fi
# A deeper queue than slcan's 10: the serve's bursts wait in the qdisc while the line drains
# (slcan stops the queue until the tty has taken the previous line) instead of ENOBUFS.
ip link set slc0 txqueuelen 1000
ip link set slc0 up || { log "slc0 up failed"; exit 3; }

pids=()
if [ "$candump" = 1 ]; then
  candump -L slc0 > "$work/candump.log" 2>&1 &
  pids+=($!)
fi
"$sim" serve --bus socketcan:slc0 --physics ode --seed "$seed" --exit-after-idle 30 \
  --status-every 0 2> "$work/serve.log" &
serve_pid=$!
: > "$work/uml_ready"

while [ ! -e "$work/qemu_done" ] && kill -0 "$serve_pid" 2> /dev/null; do sleep 0.2; done
kill -TERM "$serve_pid" 2> /dev/null
wait "$serve_pid"
serve_rc=$?
ip -s -d link show slc0 > "$work/slc0_stats.txt" 2>&1
for p in "${pids[@]}"; do kill -INT "$p" 2> /dev/null; wait "$p" 2> /dev/null; done
kill -TERM "$slcand_pid" 2> /dev/null
wait "$slcand_pid" 2> /dev/null
echo "serve exit $serve_rc" > "$work/serve_rc"
# 143: stopped by our SIGTERM after QEMU ended; 0: idle exit.
case "$serve_rc" in 0|143) exit 0 ;; *) exit "$serve_rc" ;; esac
