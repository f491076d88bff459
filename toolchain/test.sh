#!/usr/bin/env bash
# The whole test suite, from a bare Debian 12 machine: installs packages, builds the host
# tree, the Cortex-M7 firmware and the ZynqMP firmware (docs/deploy.md), runs the host tests
# (incl. real vcan inside User-mode Linux), the firmware tests under QEMU, and a bounded libFuzzer run of the CAN decoders, the
# journal and the files the host tools read back; then prints the encoder's figures (every
# kernel path beside LibTorch, the board image's instructions per layer) and the Python
# package's (tests/python/bench_python.py).
set -euo pipefail
cd "$(dirname "$0")/.."
bash toolchain/setup-debian.sh
echo "== host build"
cmake --preset default
cmake --build --preset default
echo "== Cortex-M7 build"
cmake --preset cortex-m7
cmake --build --preset cortex-m7
echo "== firmware tests under QEMU (Cortex-M7)"
ctest --preset cortex-m7
echo "== ZynqMP build (Cortex-A53 in AArch32, the CAN controller driver) and its tests under QEMU"
cmake --preset zynqmp
cmake --build --preset zynqmp
ctest --preset zynqmp
echo "== fuzz targets (frame codecs, ISO-TP, SLCAN, journal, host files) under ASan + UBSan, bounded"
bash tests/fuzz/run.sh 200000 60
echo "== host tests"
ctest --preset default
echo "== encoder figures (label bench: every kernel path beside LibTorch, the board image per layer)"
bash tests/nn/encoder_figures.sh build/default/tests/nn build/m7/tests/board/firmware.board.cycles.elf
echo "== python figures (label bench: 10,000 MGE-EFR episodes from Python beside the same run in C++)"
PYTHONPATH=build/default/host_tools/python /usr/bin/python3 tests/python/bench_python.py
