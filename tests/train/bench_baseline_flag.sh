#!/usr/bin/env bash
# Training speed of curio-train with a benchmark-baseline flag (the old behaviour) against its
# default: the same recipe twice, one thread, one after the other, printed as a ratio; the two
# runs must end with the same loss (the flag may change speed, never the numbers).
# Usage: bench_baseline_flag.sh CURIO_TRAIN FLAG "BASELINE LABEL" "DEFAULT LABEL" ITERATIONS WORK_DIR
#        [TRAIN OPTIONS...]   (bench_allocator.sh and bench_denormals.sh call it)
set -euo pipefail
[ $# -ge 6 ] || { echo "usage: bench_baseline_flag.sh CURIO_TRAIN FLAG BASELINE_LABEL DEFAULT_LABEL ITERATIONS WORK_DIR [TRAIN OPTIONS...]" >&2; exit 2; }
bin=$1; flag=$2; base_label=$3; default_label=$4; its=$5; work=$6
shift 6
mkdir -p "$work"
common=(train --kind beta-vae --threads 1 --batch 32 --iterations "$its" --eval-every 0
        --report-images 0 --checkpoint-every 1000000 --log-every "$its" --dataset-size 2000 "$@")
# Fields of a log's last progress line ("it 60/60 | 17.40 it/s | loss 1728.31 recon ...").
rate() { grep '^it ' "$1" | tail -1 | sed 's#.*| \([0-9.]*\) it/s.*#\1#'; }
loss() { grep '^it ' "$1" | tail -1 | sed 's#.*| loss \([0-9.]*\).*#\1#'; }
rm -rf "$work/baseline" "$work/default"
"$bin" "${common[@]}" --out "$work/baseline" "$flag" > "$work/baseline.log"
"$bin" "${common[@]}" --out "$work/default" > "$work/default.log"
a=$(rate "$work/baseline.log"); b=$(rate "$work/default.log")
loss_a=$(loss "$work/baseline.log"); loss_b=$(loss "$work/default.log")
echo "curio-train, batch 32, 1 thread, $its iterations${*:+, $*}:"
printf '  %s %s it/s (final loss %s)\n' "$base_label ($flag):" "$a" "$loss_a"
printf '  %s %s it/s (final loss %s)\n' "$default_label:" "$b" "$loss_b"
awk -v a="$a" -v b="$b" 'BEGIN { printf "  speed-up: %.2fx\n", b / a }'
[ "$loss_a" = "$loss_b" ] || { echo "the two runs differ: $flag changed the numbers"; exit 1; }
