// The factor report: how the latent means μ relate to the four ground-truth factors (ball x, ball
// y, distractor x, distractor y) and whether a trained model meets the criteria (docs/training.md,
// "The factor report"). Pure computation over arrays; the trainer fills them from a model.
#pragma once
#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "host_tools/vae/factor_metrics.hpp"

namespace curio::train {

inline constexpr int kFactors = 4;
inline constexpr std::array<const char*, kFactors> kFactorNames = {"ball_x", "ball_y",
                                                                   "distractor_x", "distractor_y"};

struct Criteria {
  double active_kl = 0.5;     // a latent with mean KL above this (nats) is active
  int beta_vae_active = 4;    // β-VAE: exactly this many active latents
  double own_corr = 0.9;      // each active latent |corr| ≥ this with one factor
  double other_corr = 0.3;    // … and ≤ this with every other
  double beta_vae_mig = 0.4;  // β-VAE: MIG ≥ this
  int vae_min_active = 8;     // VAE: at least this many active latents
  double vae_max_mig = 0.2;   // VAE: entangled means MIG below this
};

struct FactorReport {
  std::string model;                       // "beta-vae" or "vae"
  int images = 0;
  std::vector<double> kl_per_latent;       // nats, mean over the images
  std::vector<std::vector<double>> corr;   // corr[latent][factor], Pearson of μ
  MigResult mig_all;                       // over all latents (the standard MIG)
  MigResult mig_active;                    // over active latents only (diagnostic)
  std::vector<int> active;                 // indices with KL > active_kl, by decreasing KL
  std::vector<int> best_factor;            // per latent: argmax |corr|
  bool pass = false;
  std::vector<std::string> reasons;        // why it failed (empty when it passed)
};

// mu[l][i] latent means, factors[k][i] ground truth, kl_per_latent[l] mean KL.
FactorReport make_factor_report(const std::string& model, const std::vector<double>& kl_per_latent,
                                const std::vector<std::vector<double>>& mu,
                                const std::vector<std::vector<double>>& factors,
                                const Criteria& criteria = {});

nlohmann::json to_json(const FactorReport& report, const Criteria& criteria = {});

// One line per active latent ("z3 KL 3.12  ball_x |r| 0.97 ...") plus the verdict.
std::string summary_text(const FactorReport& report);

}  // namespace curio::train
