#!/usr/bin/env bash
# Installs every Debian 12 package Curio needs (host build, tests, trainer, cross build,
# User-mode Linux vcan, fuzzing, Slurm). Idempotent: does nothing when all are present.
# Run as root (or with sudo available).
set -euo pipefail

PACKAGES=(
  # build
  cmake ninja-build g++ pkg-config git
  # scripts and checks (toolchain/check_layers.py, the DBC check, UML and Slurm helpers)
  python3
  # libraries
  libeigen3-dev libode-dev libcli11-dev nlohmann-json3-dev libfmt-dev libpng-dev libstb-dev
  libtbb-dev nettle-dev
  # tests and benchmarks (oneDNN and XNNPACK: the int8 encoder beside them, tests/nn)
  libgtest-dev libgmock-dev libbenchmark-dev libdnnl-dev libxnnpack-dev libpthreadpool-dev
  # plots
  gnuplot-nox
  # the curio Python package (host_tools/python, docs/python.md) and its tests
  pybind11-dev python3-dev python3-pybind11 python3-numpy python3-matplotlib python3-pytest
  python3-venv
  # trainer: LibTorch on OpenBLAS (OpenMP variant: 4–5× faster than the reference BLAS)
  libtorch-dev libopenblas0-openmp
  # Cortex-M7 cross build and QEMU
  gcc-arm-none-eabi libnewlib-arm-none-eabi libstdc++-arm-none-eabi-dev qemu-system-arm
  # CAN: User-mode Linux with vcan, tools, DBC cross-check
  user-mode-linux busybox-static iproute2 can-utils python3-canmatrix
  # a camera on the controller's computer: ffmpeg reads the simulated stream in the tests
  # (tests/app/camera_stream.sh) as it reads a V4L2 or RTSP camera on a bench (docs/hil.md)
  ffmpeg
  # fuzzing and sanitizers
  clang libclang-rt-14-dev
  # a single-node Slurm for the cluster test (tests/lab/slurm_campaign.sh; docs/cluster.md)
  slurm-wlm munge jq
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} Debian packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  SUDO="sudo"
fi
echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends -o DPkg::Lock::Timeout=600 "${missing[@]}"
echo "setup: done"
