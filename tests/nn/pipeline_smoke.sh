#!/usr/bin/env bash
# The whole learned-goal-space pipeline at toy size, as CI runs it: a few hundred training
# iterations → export → int8 quantization and header emission → `curio-quantize check` →
# the emitted header compiled with the firmware encoder and run on a camera frame.
# usage: pipeline_smoke.sh CURIO_TRAIN CURIO_QUANTIZE CXX REPO_DIR CURIO_NN_LIB WORK_DIR
set -euo pipefail
train=$1 quantize=$2 cxx=$3 repo=$4 nnlib=$5 work=$6
rm -rf "$work" && mkdir -p "$work/models"
"$train" train --kind beta-vae --out "$work/run" --iterations 300 --batch 16 \
  --dataset-size 512 --capacity-iters 200 --eval-every 0 --report-images 0 --log-every 100 \
  --checkpoint-every 300
"$train" export --checkpoint "$work/run" --out "$work/models" --name smoke --kl-images 100
"$quantize" quantize --model "$work/models/smoke.cfm" --images 50 --header "$work/models/smoke_weights.hpp"
"$quantize" check --header "$work/models/smoke_weights.hpp" --model "$work/models/smoke.cfm"
cat > "$work/use_header.cpp" <<'CPP'
// Compiles the emitted header with the firmware encoder and encodes one frame.
#include <cmath>
#include <cstdio>

#include "firmware/nn/encoder.hpp"
#include "smoke_weights.hpp"

int main() {
  static uint8_t frame[64 * 64 * 3] = {};
  for (int i = 0; i < 64 * 64 * 3; i += 3) frame[i] = frame[i + 1] = (i / 3) % 64 < 8 ? 255 : 0;
  static curio::nn::Encoder encoder(curio::nn::smoke::kEncoderModel);
  float mu[curio::nn::kLatents];
  if (encoder.encode(frame, mu) != curio::nn::Status::kOk) return 1;
  for (float m : mu)
    if (!std::isfinite(m)) return 2;
  std::printf("smoke header: kl order starts with z%d, mu[0] = %g\n", curio::nn::smoke::kKlOrder[0],
              static_cast<double>(mu[0]));
  return 0;
}
CPP
"$cxx" -std=c++20 -O1 -Wall -Wextra -Werror -I "$repo" -I "$work/models" \
  "$work/use_header.cpp" "$nnlib" -o "$work/use_header"
"$work/use_header"
