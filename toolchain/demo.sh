#!/usr/bin/env bash
# The main job, from a bare Debian 12 machine: installs packages, builds, and runs a short
# engineered-feature campaign (RPE, RGE-EFR, MGE-EFR × 3 seeds, kinematic arm) that prints
# the exploration ratios and writes CSV/JSON results and PNG plots to out/demo/.
# Extra arguments go to `curio-lab run` (e.g. --physics ode --seeds 0-14).
set -euo pipefail
cd "$(dirname "$0")/.."
bash toolchain/setup-debian.sh
cmake --preset default >/dev/null
cmake --build --preset default
./build/default/host_tools/lab/curio-lab run --algos RPE,RGE-EFR,MGE-EFR --seeds 0-2 \
  --noise 0.05 --physics kinematic --episodes 10000 --bootstrap 100 --competence-clip 1 \
  --out out/demo "$@"
