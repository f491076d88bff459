// A training recipe: every knob of the schedule (the network and objective are fixed by
// SPEC §3), and the β, capacity C, learning rate and ball spread it gives at each iteration.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "host_tools/vae/trial_options.hpp"

namespace curio::train {

// The shipped recipe's knobs (train_beta_vae.sh sets or relies on each), in the order a run
// uses them: objective, optimiser, latent stages, initialisation, data; then `trial`, the
// options only the recorded trials use.
struct Recipe {
  // Objective: "beta-vae" (β, capacity C ramped to capacity_max) or "vae" (β = 1, C = 0).
  std::string model = "beta-vae";
  double beta = 150.0;             // β-VAE only
  double capacity_min = 0.0;       // C at the start of the ramp (nats)
  double capacity_max = 12.0;      // C at the end of the ramp (nats)
  int64_t capacity_iters = 15000;  // ramp length, counted from the end of the warm-up
  // Optimiser: Adam at a constant lr (the trials shape it: TrialOptions::lr_warmup, …).
  int64_t iterations = 30000;
  int64_t batch = 64;
  double lr = 5e-4;
  // Latent stages: (iteration, count) pairs, iterations increasing. From each iteration on,
  // `count` latents train and the rest are held at the prior (zero weights, KL 0). When the
  // count rises, held latents (lowest index first) get fresh weights; when it falls, the
  // trained latents that matter least (TrialOptions::prune_by) are held (pruned). Empty: all
  // 10 throughout.
  std::vector<std::pair<int64_t, int>> latent_stages;
  // Initialisation: Kaiming, then enc.fc_out weights × out_init_scale (small: KL ≈ 0 at
  // start); or the weights of another run's checkpoint (fresh Adam state) when init_from ≠ "".
  double out_init_scale = 1.0;
  std::string init_from;
  // Data: dataset_size training images drawn with `seed` (which also seeds init, batches and
  // noise). The ball lies in [-ball_spread, ball_spread]² (1: SPEC §3). Below 1 this is a
  // curriculum phase outside SPEC §3 (the held-out checks always use the full range).
  // With ball_spread_iters > 0 the spread moves linearly from ball_spread to ball_spread_to
  // over the run's first ball_spread_iters iterations (the set is re-rendered in steps of
  // 1/32, one pixel of the ball's half-range); 0: the spread stays at ball_spread.
  int64_t dataset_size = 50000;
  uint64_t seed = 1;
  double ball_spread = 1.0;
  double ball_spread_to = 1.0;
  int64_t ball_spread_iters = 0;
  // Non-empty: train on the scenes of this CSV (curio-lab run --save-scenes: the images an
  // exploration's agent saw) instead of SPEC §3's uniform set; dataset_size becomes its row
  // count. Held-out checks and reports keep SPEC §3's uniform scenes (evaluation only).
  std::string scenes_file;

  TrialOptions trial;

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

// Latents trained at an iteration under recipe.latent_stages (10 when there are none).
int trained_latents(const Recipe& recipe, int64_t iteration);
// Parses "0:2,1500:4,4000:10"; throws std::invalid_argument with the reason on bad text.
std::vector<std::pair<int64_t, int>> parse_latent_stages(const std::string& text);

nlohmann::json to_json(const Recipe& recipe);
Recipe recipe_from_json(const nlohmann::json& j);

}  // namespace curio::train
