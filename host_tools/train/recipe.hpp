// A training recipe: every knob of the schedule (the network and objective are fixed by
// SPEC §3), and the β, capacity C and learning rate it gives at each iteration.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace curio::train {

struct Recipe {
  std::string model = "beta-vae";  // "beta-vae" (β = 150, C ramp) or "vae" (β = 1, C = 0)
  int64_t iterations = 30000;
  int64_t batch = 64;
  double lr = 5e-4;
  int64_t lr_warmup = 0;        // lr rises linearly from 0 over these iterations
  int64_t lr_decay_from = -1;   // from here (if ≥ 0) lr falls linearly to lr_final at the end
  double lr_final = 0.0;
  double beta = 150.0;          // β-VAE only
  double capacity_min = 0.0;    // C at the start of the ramp (nats)
  double capacity_max = 12.0;   // C at the end of the ramp (nats)
  int64_t capacity_iters = 15000;  // ramp length, counted from the end of the warm-up
  int64_t warmup = 0;           // plain-VAE iterations (β = 1, C = 0) before the β-VAE loss
  int64_t beta_ramp = 0;        // after warm-up β grows linearly from 1 to β over these
  // At the end of the warm-up, re-initialise the layers on either side of the latents
  // (enc.fc_out, dec.fc1) and their Adam state: the β-VAE then grows its code from zero on
  // top of the warmed-up feature layers instead of squeezing the VAE's distributed code.
  bool reinit_after_warmup = false;
  // With reinit_after_warmup: re-initialise the whole decoder too (only the encoder's
  // feature layers keep what the warm-up learnt).
  bool reinit_decoder = false;
  // Latent stages: (iteration, count) pairs, iterations increasing. From each iteration on,
  // `count` latents train and the rest are held at the prior (zero weights, KL 0). When the
  // count rises, held latents (lowest index first) get fresh weights; when it falls, the
  // trained latents that matter least (prune_by) are held (pruned). Empty: all 10 throughout.
  std::vector<std::pair<int64_t, int>> latent_stages;
  // Which latents a falling stage count holds: "kl" (lowest recent KL) or "recon" (smallest
  // loss of reconstruction when the latent alone is set to the prior mean).
  std::string prune_by = "kl";
  double out_init_scale = 1.0;  // enc.fc_out weights × this after init (small: KL ≈ 0 at start)
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
  // (mean activation ≤ recycle_threshold × the layer's mean; see Vae::recycle_dormant_encoder_units)
  // with outgoing weights Kaiming × recycle_outgoing_scale (0: zero, the output is unchanged).
  int64_t recycle_every = 0;
  double recycle_threshold = 0.1;
  double recycle_outgoing_scale = 0.0;
  bool recycle_decoder_too = false;  // recycle_every also recycles the decoder's dormant units
  // At iteration revive_at (≥ 0; −1: never) revive the code once (Vae::revive): dormant encoder
  // and decoder units recycled as above (or a fresh decoder), fresh read-out (× out_init_scale) for every
  // latent below 0.1 nats, fresh Adam state.
  int64_t revive_at = -1;
  bool revive_fresh_decoder = false;  // revival re-initialises the decoder (else recycles it)
  // In an --init-from run: the enc.fc_out rows (μ and log σ²) of the latents active in the
  // initial model (KL > 0.5) stay exactly as they are, so a KL deficit cannot be absorbed by
  // sharpening them and must lift other latents.
  bool freeze_active_readout = false;
  // Start from the weights of another run's checkpoint (fresh Adam state); "" = `init`.
  std::string init_from;
  // Training images draw the ball in [-ball_spread, ball_spread]² (1: SPEC §3). Below 1 this
  // is a curriculum phase outside SPEC §3 (the held-out checks always use the full range).
  double ball_spread = 1.0;
  // With ball_spread_iters > 0 the spread moves linearly from ball_spread to ball_spread_to
  // over the run's first ball_spread_iters iterations (the set is re-rendered in steps of
  // 1/32, one pixel of the ball's half-range); 0: the spread stays at ball_spread.
  double ball_spread_to = 1.0;
  int64_t ball_spread_iters = 0;
  int64_t dataset_size = 50000;
  uint64_t seed = 1;
  // Non-empty: train on the scenes of this CSV (curio-lab run --save-scenes: the images an
  // exploration's agent saw) instead of SPEC §3's uniform set; dataset_size becomes its row
  // count. Held-out checks and reports keep SPEC §3's uniform scenes (evaluation only).
  std::string scenes_file;

  bool is_beta_vae() const { return model == "beta-vae"; }
};

struct ScheduleAt {
  double beta;
  double capacity;
  double lr;
  double ball_spread;  // of the training images, rounded to steps of kBallSpreadStep
};

// The ball-spread ramp re-renders the training set when the spread has moved by a step.
inline constexpr double kBallSpreadStep = 1.0 / 32.0;

ScheduleAt schedule_at(const Recipe& recipe, int64_t iteration);

// Whether the encoder's feature layers are frozen at an iteration: from freeze_encoder_from
// (≥ 0) up to freeze_encoder_to (exclusive), or to the end when freeze_encoder_to < 0.
bool encoder_frozen_at(const Recipe& recipe, int64_t iteration);

// Latents trained at an iteration under recipe.latent_stages (10 when there are none).
int trained_latents(const Recipe& recipe, int64_t iteration);
// Parses "0:2,1500:4,4000:10"; throws std::invalid_argument with the reason on bad text.
std::vector<std::pair<int64_t, int>> parse_latent_stages(const std::string& text);

nlohmann::json to_json(const Recipe& recipe);
Recipe recipe_from_json(const nlohmann::json& j);

}  // namespace curio::train
