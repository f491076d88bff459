#!/bin/sh
# Runs a ZynqMP image under QEMU's xlnx-zcu102 (the toolchain's CMAKE_CROSSCOMPILING_EMULATOR):
#   run-zcu102.sh IMAGE.elf [ARG...]
# ARGs become the semihosting command line. APU core 0 (Cortex-A53) starts at the ELF entry in
# AArch64 EL3 (secure=on; toolchain/boards/zcu102/startup.S drops to AArch32). Both CAN
# controllers join one QEMU can-bus (canbus0 = canbus1 = the QEMU can-bus "curiocan"). Environment:
#   ZCU102_SERIAL  UART0's chardev (default stdio; e.g. unix:/path/sock for a host peer)
#   ZCU102_QEMU    extra QEMU options, split on spaces (e.g. "-object can-host-socketcan,
#                  id=h0,if=vcan0,canbus=curiocan" to bridge the bus to a Linux interface)
# The exit status is the image's (semihosting SYS_EXIT_EXTENDED).
if [ $# -lt 1 ]; then
  sed -n '2,11p' "$0" >&2
  exit 2
fi
image=$1
shift
semi="enable=on,target=native"
for a in "$@"; do semi="$semi,arg=$a"; done
# shellcheck disable=SC2086
exec qemu-system-aarch64 -M xlnx-zcu102,secure=on,canbus0=curiocan,canbus1=curiocan \
  -object can-bus,id=curiocan -audiodev none,id=snd0 -nographic -monitor none \
  -serial "${ZCU102_SERIAL:-stdio}" -semihosting-config "$semi" \
  -device "loader,file=$image,cpu-num=0" ${ZCU102_QEMU:-}
