#!/usr/bin/env bash
# Training speed with glibc's default malloc thresholds vs curio-train's default (freed tensor
# memory kept in the process): the same β-VAE recipe twice, one thread, printed as a ratio.
# Usage: bench_allocator.sh CURIO_TRAIN [ITERATIONS=400] [WORK_DIR=mktemp]
set -euo pipefail
bin=${1:?usage: bench_allocator.sh CURIO_TRAIN [ITERATIONS] [WORK_DIR]}
exec "$(dirname "$0")/bench_baseline_flag.sh" "$bin" --glibc-default-allocator \
  "glibc default malloc thresholds" "freed memory kept in process" "${2:-400}" "${3:-$(mktemp -d)}"
