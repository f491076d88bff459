#!/usr/bin/env bash
# Training speed with glibc's default malloc thresholds vs curio-train's default (freed tensor
# memory kept in the process): the same β-VAE recipe twice, one thread, printed as a ratio.
# Usage: bench_allocator.sh CURIO_TRAIN [ITERATIONS=400] [WORK_DIR=mktemp]
set -euo pipefail
bin=${1:?usage: bench_allocator.sh CURIO_TRAIN [ITERATIONS] [WORK_DIR]}
its=${2:-400}
work=${3:-$(mktemp -d)}
mkdir -p "$work"
common=(train --model beta-vae --threads 1 --batch 32 --iterations "$its" --eval-every 0
        --report-images 0 --checkpoint-every 1000000 --log-every "$its" --dataset-size 2000)
# Fields of a log's last progress line ("it 60/60 | 17.40 it/s | loss 1728.31 recon ...").
rate() { grep '^it ' "$1" | tail -1 | sed 's#.*| \([0-9.]*\) it/s.*#\1#'; }
loss() { grep '^it ' "$1" | tail -1 | sed 's#.*| loss \([0-9.]*\).*#\1#'; }
rm -rf "$work/default" "$work/kept"
"$bin" "${common[@]}" --out "$work/default" --glibc-default-allocator > "$work/default.log"
"$bin" "${common[@]}" --out "$work/kept" > "$work/kept.log"
a=$(rate "$work/default.log"); b=$(rate "$work/kept.log")
loss_a=$(loss "$work/default.log"); loss_b=$(loss "$work/kept.log")
echo "curio-train, batch 32, 1 thread, $its iterations:"
echo "  glibc default malloc thresholds: $a it/s (final loss $loss_a)"
echo "  freed memory kept in process:    $b it/s (final loss $loss_b)"
awk -v a="$a" -v b="$b" 'BEGIN { printf "  speed-up: %.2fx\n", b / a }'
[ "$loss_a" = "$loss_b" ] || { echo "the two runs differ: allocator settings changed the numbers"; exit 1; }
