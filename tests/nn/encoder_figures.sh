#!/usr/bin/env bash
# The int8 encoder's speed on every path in one table: host µs per image (batch 1, one
# thread) beside LibTorch fp32 measured in the same process, for each build of the kernels
# that this CPU runs, then the Cortex-M7 board image's instruction counts per layer (QEMU
# -icount) beside CMSIS-NN when that image has been built (toolchain/build-cortex-m7.sh), and
# the shipped encoder beside oneDNN and XNNPACK where that benchmark was built.
# Usage: encoder_figures.sh <dir with curio-bench-encoder-torch*> [<firmware.board.cycles.elf>]
# Fails only if a benchmark fails; the figures are for reading (docs/deploy.md, docs/encoder.md).
set -euo pipefail
dir=$1
elf=${2:-}
min_time=${CURIO_BENCH_MIN_TIME:-0.5}
echo "== int8 encoder on this host: one image, batch 1, one thread, beside LibTorch fp32 (same process)"
printf '  %-44s %10s %12s %8s\n' "kernels built with (path taken)" "int8 us" "LibTorch us" "ratio"
for suffix in "" -avx2-vnni -avx2 -portable; do
  bin=$dir/curio-bench-encoder-torch$suffix
  [[ -x $bin ]] || continue
  filter='BM_Int8Encoder$|BM_TorchEncoderFp32$'
  [[ -z $suffix ]] && filter='.'  # the native build also runs the batched benchmarks
  out=$("$bin" --benchmark_min_time="$min_time" --benchmark_repetitions=3 --benchmark_color=false \
          --benchmark_filter="$filter" 2>&1) || { echo "$out"; echo "FAIL: $bin"; exit 1; }
  [[ -z $suffix ]] && batch_line=$(grep 'per image, batch' <<<"$out" || true)
  path=$(grep -m1 -o 'batch 1, 1 thread, [a-z0-9-]*' <<<"$out" | sed 's/.*thread, //')
  line=$(grep 'per image:' <<<"$out")
  int8=$(sed -E 's/.*int8 ([0-9.]+) us.*/\1/' <<<"$line")
  torch=$(sed -E 's/.*LibTorch fp32 ([0-9.]+) us.*/\1/' <<<"$line")
  ratio=$(sed -E 's/.*int8 is ([0-9.]+)x.*/\1/' <<<"$line")
  case $suffix in
    "") name="-march=native" ;;
    -avx2-vnni) name="-march=x86-64-v3 -mavxvnni" ;;
    -avx2) name="-march=x86-64-v3" ;;
    -portable) name="portable loops, -march=native" ;;
  esac
  printf '  %-44s %10s %12s %7sx\n' "$name ($path)" "$int8" "$torch" "$ratio"
done
[[ -n ${batch_line:-} ]] && echo "  native build, $batch_line"
engines=$dir/curio-bench-encoder-engines
if [[ ${CURIO_FIGURES_SKIP_ENGINES:-0} == 1 ]]; then
  echo "== oneDNN / XNNPACK comparison: skipped here (CURIO_FIGURES_SKIP_ENGINES=1; the ctest bench_encoder_engines runs it)"
elif [[ -x $engines ]]; then
  echo "== the shipped encoder beside oneDNN and XNNPACK (int8) and LibTorch fp32, same process"
  "$engines" --quick | sed 's/^/  /' || { echo "FAIL: $engines"; exit 1; }
else
  echo "== oneDNN / XNNPACK comparison: not built (needs libdnnl-dev, libxnnpack-dev, libpthreadpool-dev)"
fi
if [[ -n $elf && -f $elf ]] && command -v qemu-system-arm >/dev/null; then
  echo "== Cortex-M7 board image (QEMU mps2-an500, -icount shift=0): instructions"
  qemu-system-arm -M mps2-an500 -nographic -monitor none -serial none \
    -semihosting-config enable=on,target=native -icount shift=0 -kernel "$elf" 2>&1 | tr -d '\r' |
    sed -n '/int8 beta-VAE encoder call/,/layers equal/p'
else
  echo "== Cortex-M7 figures: no board image at ${elf:-<none>} (build it with toolchain/build-cortex-m7.sh)"
fi
