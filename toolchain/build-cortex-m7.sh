#!/usr/bin/env bash
# Cross-builds the firmware core for Cortex-M7 (arm-none-eabi-gcc, newlib-nano) in build/m7,
# runs the firmware tests under QEMU (mps2-an500) and prints the images' flash/RAM sizes.
# Usage: toolchain/build-cortex-m7.sh [extra cmake configure args]
set -euo pipefail
cd "$(dirname "$0")/.."
build=build/m7
cmake -S . -B "$build" -G Ninja \
  -DCMAKE_TOOLCHAIN_FILE="$PWD/toolchain/arm-none-eabi-cortex-m7.cmake" \
  -DCURIO_FIRMWARE_ONLY=ON -DCMAKE_BUILD_TYPE=MinSizeRel "$@"
cmake --build "$build" -j2
echo "== firmware libraries (text = flash, data + bss = RAM)"
find "$build/firmware" -name 'libcurio_*.a' -print0 | sort -z | while IFS= read -r -d '' lib; do
  arm-none-eabi-size -t "$lib" | tail -1 | sed "s|(TOTALS)|$(basename "$lib")|"
done
echo "== test images"
find "$build" -name '*.elf' -print0 | sort -z | xargs -0 -r arm-none-eabi-size
echo "== tests under QEMU"
ctest --test-dir "$build" --output-on-failure -j2
