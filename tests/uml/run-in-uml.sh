#!/usr/bin/env bash
# Runs a command inside User-mode Linux with a real kernel CAN stack (vcan0, CAN FD, MTU 72)
# and returns its exit code. The host's / is the (read-only) root; the repository (and any
# --rw DIR) is mounted writable at the same path, so build trees work unchanged.
#
#   tests/uml/run-in-uml.sh [--rw DIR]... [--vcan N] [--mem SIZE] [--timeout S] [--no-batch]
#                           [--serial-fd N] [--] CMD [ARGS...]
#
# Inside: lo is up, vcan0..vcan{N-1} exist (CAN FD, MTU 72) and vcan_classic (classic CAN,
# MTU 16: the arm protocol's classic profile), TMPDIR=/run (tmpfs), cwd = the caller's cwd,
# CURIO_*/GTEST_* variables are passed through. One CPU; syscalls cost ~20 µs; no ASan.
# --serial-fd N: UML's serial line 1 (/dev/ttyS1 inside, char 4:65) is the host's open file
# descriptor N (ssl1=fd:N, e.g. one end of a socketpair; tests/uml/qemu_slcan_uml.sh).
# CMD runs under SCHED_BATCH (chrt -b 0; --no-batch to keep SCHED_OTHER): without wakeup
# preemption a receiver no longer preempts its sender after every frame of a sendmmsg batch,
# and each UML context switch is expensive (docs/can.md: ~4x more control periods per second).
# Exit codes: the command's; 1 if UML died while it ran (console log printed); 125 if UML died
# twice before it started or its setup failed (nothing tested: ctest counts it as skipped).
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
rw=("$repo")
vcans=1
mem=512M
timeout_s=600
sched=(chrt -b 0)
serial=()
while [ $# -gt 0 ]; do
  case "$1" in
    --rw) rw+=("$(cd "$2" && pwd)"); shift 2 ;;
    --vcan) vcans=$2; shift 2 ;;
    --mem) mem=$2; shift 2 ;;
    --timeout) timeout_s=$2; shift 2 ;;
    --no-batch) sched=(); shift ;;
    --serial-fd) serial=("ssl1=fd:$2"); shift 2 ;;
    --) shift; break ;;
    -h|--help) sed -n '2,18p' "$0"; exit 0 ;;
    *) break ;;
  esac
done
if [ $# -eq 0 ]; then
  echo "run-in-uml: no command given (see --help)" >&2
  exit 2
fi
uml=$(command -v linux.uml || true)
busybox=$(command -v busybox || true)
if [ -z "$uml" ] || [ -z "$busybox" ]; then
  echo "run-in-uml: needs Debian packages user-mode-linux and busybox-static" >&2
  exit 125
fi

work=$(mktemp -d "${TMPDIR:-/tmp}/curio-uml.XXXXXX")
trap 'rm -rf "$work"' EXIT
rw+=("$work")

{
  echo '#!/bin/bash'
  echo 'export PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin HOME=/root TMPDIR=/run'
  echo "bb=$busybox"
  echo '$bb mount -t proc proc /proc; $bb mount -t sysfs sysfs /sys; $bb mount -t tmpfs tmpfs /run'
  for d in "${rw[@]}"; do printf '$bb mount -t hostfs hostfs %q -o %q\n' "$d" "$d"; done
  printf 'work=%q\n' "$work"
  cat <<'INIT'
fail() { echo "run-in-uml (inside): $*" > "$work/setup-error"; $bb poweroff -f; }
m=/usr/lib/uml/modules/$(uname -r)/kernel
for k in drivers/net/can/dev/can-dev net/can/can net/can/can-raw net/can/can-bcm \
         net/can/can-gw drivers/net/can/vcan; do
  $bb insmod "$m/$k.ko" || fail "insmod $k failed"
done
ip link set lo up || fail "lo up failed"
INIT
  echo "for i in \$(seq 0 $((vcans - 1))); do"
  echo '  ip link add dev vcan$i type vcan && ip link set vcan$i mtu 72 up || fail "vcan$i setup failed"'
  echo 'done'
  echo 'ip link add dev vcan_classic type vcan && ip link set vcan_classic mtu 16 up || fail "vcan_classic setup failed"'
  while IFS='=' read -r name _; do
    case "$name" in CURIO_*|GTEST_*) printf 'export %s=%q\n' "$name" "${!name}" ;; esac
  done < <(env)
  printf 'cd %q || fail "cannot cd"\n' "$PWD"
  echo ': > "$work/started"'
  printf '%q ' "${sched[@]}" "$@"
  echo '> "$work/stdout" 2> "$work/stderr"'
  echo 'echo $? > "$work/rc"'
  echo '$bb poweroff -f'
} > "$work/init"
chmod +x "$work/init"

# UML on a host whose XSAVE area is larger than UML's ptrace buffer (a Xeon with AMX: 11,008
# bytes against UML 6.1's 2,688) cannot set its processes' FPU state and dies at its first
# process; uml_ptrace_xstate.c, preloaded into linux.uml, hands the kernel a whole buffer. It
# passes every other call through unchanged, so it is preloaded on every host where cc exists.
preload=()
if cc -O2 -shared -fPIC -o "$work/uml_ptrace_xstate.so" "$repo/tests/uml/uml_ptrace_xstate.c" \
     -ldl 2> "$work/preload-build.log"; then
  preload=(env "LD_PRELOAD=$work/uml_ptrace_xstate.so")
fi

boot() {  # boot UML with our init; console to $work/console.log
  timeout "$timeout_s" ${preload[@]+"${preload[@]}"} "$uml" mem="$mem" rootfstype=hostfs hostfs=/ ro init="$work/init" \
    con=null con0=null,fd:1 ${serial[@]+"${serial[@]}"} quiet > "$work/console.log" 2>&1 < /dev/null
}
# A UML that dies before the command starts (seen on some hosts: the UML 6.1 kernel's init
# takes SIGSEGV at its first exec, before any project code runs) is the host's failure, not
# the command's: boot once more, then give up with 125 (ctest: skipped) and name the host.
# Without the preload (no cc), a host with AMX shows "ptrace set fp regs failed, errno = 14"
# here every time, and the message below says so.
# A UML that dies after the command started was broken by the command: 1.
for attempt in 1 2; do
  set +e
  boot
  uml_rc=$?
  set -e
  [ -f "$work/started" ] && break
  echo "run-in-uml: UML died before the command started (boot $attempt, linux.uml exit $uml_rc)" >&2
  tail -n 30 "$work/console.log" >&2
  [ -f "$work/setup-error" ] && break
done
[ -f "$work/stdout" ] && cat "$work/stdout"
[ -f "$work/stderr" ] && cat "$work/stderr" >&2
if [ -f "$work/rc" ]; then
  exit "$(cat "$work/rc")"
fi
if [ -f "$work/setup-error" ]; then
  echo "run-in-uml: $(cat "$work/setup-error")" >&2
  exit 125
fi
if [ ! -f "$work/started" ]; then
  cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')
  why=""
  if grep -q 'ptrace set fp regs failed' "$work/console.log" 2>/dev/null; then
    why="UML could not load its init's FPU/XSAVE state ('ptrace set fp regs failed'):"
    grep -qw amx_tile /proc/cpuinfo && why+=" this CPU has AMX, whose XSAVE state is larger than UML's buffer"
    if [ ${#preload[@]} -eq 0 ]; then
      why+=" (install a C compiler: run-in-uml.sh then builds uml_ptrace_xstate.c, which fixes that)"
    fi
    why+=";"
  fi
  echo "run-in-uml: UML cannot boot on this host (host kernel $(uname -r), CPU ${cpu:-unknown});" \
       ${why:+"$why"} "nothing was tested" >&2
  exit 125
fi
echo "run-in-uml: the command did not complete inside UML (linux.uml exit $uml_rc)" >&2
tail -n 30 "$work/console.log" >&2
exit 1
