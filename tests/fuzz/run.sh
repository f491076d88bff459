#!/usr/bin/env bash
# Builds the libFuzzer targets with clang-14 (ASan + UBSan) in build/fuzz and runs each for
# a bounded number of inputs, keeping a corpus per target under build/fuzz/corpus/.
#   tests/fuzz/run.sh [RUNS per target, default 1000000] [max SECONDS per target, default 900]
# Exit status non-zero if a target crashed (the reproducer is written to build/fuzz/).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
runs=${1:-1000000}
secs=${2:-900}
build=${CURIO_FUZZ_BUILD:-$repo/build/fuzz}
targets=(curio_fuzz_frame_codec curio_fuzz_isotp curio_fuzz_slcan curio_fuzz_journal curio_fuzz_host_files
         curio_fuzz_camera_png)

command -v clang++-14 >/dev/null || { echo "fuzz: needs clang-14 and libclang-rt-14-dev" >&2; exit 2; }
CC=clang-14 CXX=clang++-14 cmake -S "$repo" -B "$build" -G Ninja -DCURIO_FUZZ=ON \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCURIO_BUILD_TRAINER=OFF > "$build.configure.log" 2>&1 ||
  { cat "$build.configure.log" >&2; exit 2; }
cmake --build "$build" --target "${targets[@]}" -j2

status=0
for t in "${targets[@]}"; do
  corpus="$build/corpus/$t"
  mkdir -p "$corpus"
  echo "== $t: up to $runs inputs or $secs s"
  start=$(date +%s)
  if (cd "$build" && "./tests/hal/fuzz/$t" -runs="$runs" -max_total_time="$secs" \
        -print_final_stats=1 "$corpus" 2>&1 | tee "$build/$t.log" | grep -E "^#[0-9]+.*(DONE|pulse)|stat::number_of_executed_units|ERROR|SUMMARY"); then :; fi
  if grep -q "ERROR: libFuzzer\|SUMMARY: .*Sanitizer\|runtime error" "$build/$t.log"; then
    echo "== $t: FAILED (see $build/$t.log)"
    status=1
  else
    echo "== $t: ok, $(grep -o 'stat::number_of_executed_units: [0-9]*' "$build/$t.log" | grep -o '[0-9]*$') inputs in $(( $(date +%s) - start )) s"
  fi
done
exit $status
