#!/usr/bin/env bash
# The bus numbers in docs/can.md, measured inside User-mode Linux (vcan0 and the UDP bus) and
# on the host (UDP, loopback):   tests/uml/bench-can.sh [BUILD_DIR, default build/default]
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=$(cd "${1:-$repo/build/default}" && pwd)
tool="$build/host_tools/can_tools/curio-can"
[ -x "$tool" ] || { echo "bench-can: build curio-can first ($tool)" >&2; exit 2; }
echo "host: $(nproc) CPUs, load average $(cut -d' ' -f1-3 /proc/loadavg)"
"$tool" bench --bus udp:127.0.0.1:47300
"$tool" bench --bus udp:127.0.0.1:47300 --fd
"$tool" episodes --bus udp:127.0.0.1:47300 -e 50
"$tool" episodes --bus loopback -e 50
echo "inside User-mode Linux (SCHED_BATCH):"
"$repo/tests/uml/run-in-uml.sh" --timeout 600 bash -c "
  for url in socketcan:vcan0 udp:127.0.0.1:47300; do
    $tool bench --bus \$url; $tool bench --bus \$url --fd; $tool bench --bus \$url --in-flight 1; $tool episodes --bus \$url -e 20
  done"
