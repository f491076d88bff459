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
mkdir -p "$work"
common=(train --model beta-vae --threads 1 --batch 32 --iterations "$its" --eval-every 0
        --report-images 0 --checkpoint-every 1000000 --log-every "$its" --dataset-size 2000 "$@")
# Fields of a log's last progress line ("it 60/60 | 17.40 it/s | loss 1728.31 recon ...").
rate() { grep '^it ' "$1" | tail -1 | sed 's#.*| \([0-9.]*\) it/s.*#\1#'; }
loss() { grep '^it ' "$1" | tail -1 | sed 's#.*| loss \([0-9.]*\).*#\1#'; }
rm -rf "$work/kept" "$work/flushed"
"$bin" "${common[@]}" --out "$work/kept" --keep-denormals > "$work/kept.log"
"$bin" "${common[@]}" --out "$work/flushed" > "$work/flushed.log"
a=$(rate "$work/kept.log"); b=$(rate "$work/flushed.log")
loss_a=$(loss "$work/kept.log"); loss_b=$(loss "$work/flushed.log")
echo "curio-train, batch 32, 1 thread, $its iterations${*:+, $*}:"
echo "  denormals kept:             $a it/s (final loss $loss_a)"
echo "  denormals flushed to zero:  $b it/s (final loss $loss_b)"
awk -v a="$a" -v b="$b" 'BEGIN { printf "  speed-up: %.2fx\n", b / a }'
[ "$loss_a" = "$loss_b" ] || { echo "the two runs differ: flushing denormals changed the numbers"; exit 1; }
