// The options only the recorded trials use (docs/training.md), kept beside the recipe so every
// trial stays reproducible; the shipped recipe (train_beta_vae.sh) leaves them all at default.
#pragma once
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

namespace curio::train {

struct TrialOptions {
  // Learning-rate shape: lr rises linearly from 0 over lr_warmup iterations; from
  // lr_decay_from (if ≥ 0) it falls linearly to lr_final at the end.
  int64_t lr_warmup = 0;
  int64_t lr_decay_from = -1;
  double lr_final = 0.0;
  int64_t warmup = 0;     // plain-VAE iterations (β = 1, C = 0) before the β-VAE loss
  int64_t beta_ramp = 0;  // after warm-up β grows linearly from 1 to β over these
  // At the end of the warm-up, re-initialise the layers on either side of the latents
  // (enc.fc_out, dec.fc1) and their Adam state: the β-VAE then grows its code from zero on
  // top of the warmed-up feature layers instead of squeezing the VAE's distributed code.
  bool reinit_after_warmup = false;
  // With reinit_after_warmup: re-initialise the whole decoder too (only the encoder's
  // feature layers keep what the warm-up learnt).
  bool reinit_decoder = false;
  // Which latents a falling latent-stage count holds: "kl" (lowest recent KL) or "recon"
  // (smallest loss of reconstruction when the latent alone is set to the prior mean).
  std::string prune_by = "kl";
  // Weight initialisation: "kaiming" (Kaiming-normal weights, zero biases) or "torch-default"
  // (what LibTorch's layers get on construction, as in the reference's PyTorch code).
  std::string init = "kaiming";
  // A plain-VAE window (β = 1, C = 0) over iterations [vae_window_from, vae_window_to):
  // lets freshly released latents pick up what the code lacks before β returns.
  int64_t vae_window_from = -1;
  int64_t vae_window_to = -1;
  // The encoder's feature layers (4 convs, fc1, fc2) do not train over
  // [freeze_encoder_from, freeze_encoder_to): only enc.fc_out and the decoder learn, so the
  // features a warm-up found (both objects) cannot be unlearnt while the β-VAE code forms.
  // freeze_encoder_to < 0: the freeze lasts to the end (see encoder_frozen_at).
  int64_t freeze_encoder_from = -1;
  int64_t freeze_encoder_to = -1;
  bool freeze_convs_only = false;  // freeze only the 4 convs (fc1, fc2 keep training)
  // During the encoder freeze, hold the decoder's feature layers too (fc2 and the 4 transposed
  // convs): only the two layers touching z (enc.fc_out, dec.fc1) learn, on top of features
  // that keep rendering whatever the warm-up taught them.
  bool freeze_decoder_too = false;
  // Every recycle_every iterations (0: never), recycle the encoder's dormant feature units
  // (mean activation ≤ recycle_threshold × the layer's mean; see
  // Vae::recycle_dormant_encoder_units) with outgoing weights Kaiming × recycle_outgoing_scale (0:
  // zero, the output is unchanged).
  int64_t recycle_every = 0;
  double recycle_threshold = 0.1;
  double recycle_outgoing_scale = 0.0;
  bool recycle_decoder_too = false;  // recycle_every also recycles the decoder's dormant units
  // At iteration revive_at (≥ 0; −1: never) revive the code once (Vae::revive): dormant encoder
  // and decoder units recycled as above (or a fresh decoder), fresh read-out (× out_init_scale) for
  // every latent below 0.1 nats, fresh Adam state.
  int64_t revive_at = -1;
  bool revive_fresh_decoder = false;  // revival re-initialises the decoder (else recycles it)
  // In an --init-from run: the enc.fc_out rows (μ and log σ²) of the latents active in the
  // initial model (KL > 0.5) stay exactly as they are, so a KL deficit cannot be absorbed by
  // sharpening them and must lift other latents.
  bool freeze_active_readout = false;
};

// Whether the encoder's feature layers are frozen at an iteration: from freeze_encoder_from
// (≥ 0) up to freeze_encoder_to (exclusive), or to the end when freeze_encoder_to < 0.
bool encoder_frozen_at(const TrialOptions& trial, int64_t iteration);

// The trial options' keys of a recipe's JSON object (one flat object, as recipe.json has
// always been): written into `j`, and read back with each absent key at its default.
void add_to_json(const TrialOptions& trial, nlohmann::json& j);
TrialOptions trial_options_from_json(const nlohmann::json& j);

}  // namespace curio::train
