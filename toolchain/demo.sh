#!/usr/bin/env bash
# The main job, from a bare Debian 12 machine: installs packages, builds, then runs the
# controller (firmware/app) exploring against the simulated ODE arm over CAN: the arm is
# `curio-sim serve` (7 CiA 402 joints + camera node), the bus is SocketCAN vcan0 when this
# machine has it, else the userspace UDP bus on 127.0.0.1. Algorithm: MGE-βVAE when the
# trained weights are shipped, else MGE-EFR. Prints progress and the exploration ratio,
# writes CSV/JSON results and PNG plots to out/demo/.
# Extra arguments go to curio-controller (e.g. --seed 3 --episodes 2000 --algo RGE-EFR).
set -euo pipefail
cd "$(dirname "$0")/.."
bash toolchain/setup-debian.sh
cmake --preset default >/dev/null
cmake --build --preset default
bin=build/default

if ip link show vcan0 >/dev/null 2>&1; then bus=socketcan:vcan0; else bus=udp:127.0.0.1:29500; fi
algo=MGE-EFR
[ -f firmware/nn/models/beta_vae_weights.hpp ] && algo=MGE-βVAE
echo "demo: simulated arm and controller on $bus, algorithm $algo"

"$bin/sim/curio-sim" serve --bus "$bus" --physics ode --seed 0 --status-every 0 \
  --exit-after-idle 30 &
arm=$!
trap 'kill $arm 2>/dev/null || true' EXIT
# Each demo is a new run: the last one's out/demo (its journal included) is replaced, unless
# the extra arguments ask to --resume it.
fresh=(--replace)
for a in "$@"; do [ "$a" = --resume ] && fresh=(); done
"$bin/host_tools/controller/curio-controller" --bus "$bus" --algo "$algo" --seed 0 --out out/demo \
  "${fresh[@]}" "$@"
echo "demo: plots: $(ls out/demo/*.png | tr '\n' ' ')"
