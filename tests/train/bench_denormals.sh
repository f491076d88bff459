#!/usr/bin/env bash
# Training speed with denormal floats kept (--keep-denormals) vs curio-train's default (flushed
# to zero): the same recipe twice, one thread, printed as a ratio; the two runs must end with the
# same loss. Denormals appear once the decoder is confident, so the figure that matters comes
# from a trained model: pass --init-from CHECKPOINT (and its --scenes) as extra options.
# Usage: bench_denormals.sh CURIO_TRAIN [ITERATIONS=400] [WORK_DIR=mktemp] [TRAIN OPTIONS...]
set -euo pipefail
bin=${1:?usage: bench_denormals.sh CURIO_TRAIN [ITERATIONS] [WORK_DIR] [TRAIN OPTIONS...]}
its=${2:-400}
work=${3:-$(mktemp -d)}
shift $(( $# < 3 ? $# : 3 ))
exec "$(dirname "$0")/bench_baseline_flag.sh" "$bin" --keep-denormals "denormals kept" \
  "denormals flushed to zero" "$its" "$work" "$@"
