#!/usr/bin/env bash
# The β-VAE recipe (docs/training.md, "The β-VAE recipe"): distractor first, then the ball enters
# fresh latents while its range widens, then ICA aligns each object's pair of latents with
# the axes, then a hold at C = 12 on SPEC §3's data. ≈ 25 minutes on this 2-core machine.
#
#   bash host_tools/train/train_beta_vae.sh OUT_DIR [SEED]
#
# Re-running with the same OUT_DIR resumes: a finished stage is skipped, a killed one
# continues from its checkpoint. Then export and quantize (the last lines printed say how).
# CURIO_TRAIN overrides the trainer binary; THREADS the LibTorch threads (default 2).
set -euo pipefail

if [[ $# -lt 1 || $1 == -h || $1 == --help ]]; then
  sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'
  exit $(( $# < 1 ))
fi
out=$1
seed=${2:-2}
root=$(cd "$(dirname "$0")/../.." && pwd)
T=${CURIO_TRAIN:-$root/build/default/host_tools/train/curio-train}
[[ -x $T ]] || { echo "error: no trainer at $T (build: cmake --build build/default --target curio-train)" >&2; exit 1; }
common=(--kind beta-vae --batch 32 --lr 5e-4 --seed "$seed" --threads "${THREADS:-2}"
        --eval-every 1000)
start=$(date +%s)

# Runs one `train` stage unless it already finished (its recipe's last iteration reached).
stage() {
  local dir=$1; shift
  local resume=()
  if [[ -f $dir/done ]]; then echo "== $dir: done, skipped"; return; fi
  [[ -f $dir/checkpoint.pt ]] && resume=(--resume)
  echo "== $dir: $T train ${common[*]} --out $dir $* ${resume[*]}"
  "$T" train "${common[@]}" --out "$dir" "$@" "${resume[@]}"
  touch "$dir/done"
}

# 1. Distractor first: the ball held at the centre, two latents, C 0 → 6 (SPEC §3's data would
#    let the ball, worth ≈ 2.6× more reconstruction per nat, take every latent for good).
stage "$out/1_distractor" --iterations 8000 --ball-spread 0 --latent-stages 0:2 \
  --out-init-scale 0.01 --capacity-max 6 --capacity-iters 6000 --report-images 0
# 2. The ball enters two fresh latents while its range widens to SPEC's [-1, 1]² and C rises
#    6 → 12; the last 4,000 iterations train on SPEC §3's data.
stage "$out/2_ball" --iterations 10000 --init-from "$out/1_distractor/checkpoint.pt" \
  --latent-stages 0:4 --out-init-scale 0.3 --ball-spread 0 --ball-spread-to 1 \
  --ball-spread-iters 6000 --capacity-min 6 --capacity-max 12 --capacity-iters 6000 \
  --report-images 0
# 3. Each object's pair of latents comes out rotated in its own plane (x and y cost the same,
#    so the objective barely prefers the axes): FastICA on the active means rotates them back,
#    an exact reparameterisation of enc.fc_out and dec.fc1.
if [[ ! -f $out/3_unmixed/checkpoint.pt ]]; then
  echo "== $out/3_unmixed: $T unmix --checkpoint $out/2_ball/checkpoint.pt"
  "$T" unmix --checkpoint "$out/2_ball/checkpoint.pt" --out "$out/3_unmixed" --threads "${THREADS:-2}"
fi
# 4. Hold C = 12 on SPEC §3's data: the aligned code is stable under the β-VAE objective.
#    The six unused latents stay held at the prior (releasing them, even with 0.01-scale
#    weights, throws the reconstruction back by hundreds of nats for thousands of iterations).
stage "$out/4_tuned" --iterations 3000 --init-from "$out/3_unmixed/checkpoint.pt" \
  --latent-stages 0:4 --capacity-min 12 --capacity-max 12 --capacity-iters 1 --report-images 10000

echo "β-VAE recipe done in $(( ($(date +%s) - start) / 60 )) min (this sitting); factor report:"
echo "  $out/4_tuned/factor_report.json"
echo "export and quantize (from the repository root):"
echo "  $T export --checkpoint $out/4_tuned --out firmware/nn/models --name beta_vae \\"
echo "    --made-by \"bash host_tools/train/train_beta_vae.sh $out $seed\""
echo "  for f in factor_report.json traversal.png reconstruction.png kl_per_latent.png; do"
echo "    cp $out/4_tuned/\$f firmware/nn/models/beta_vae.\$f; done"
echo "  build/default/host_tools/quantize/curio-quantize quantize --model firmware/nn/models/beta_vae.cfm \\"
echo "    --meta firmware/nn/models/beta_vae.meta.json --name beta_vae \\"
echo "    --header firmware/nn/models/beta_vae_weights.hpp --images 1000 --seed 1 --activations per-tensor"
