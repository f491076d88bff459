// The β-VAE an online run trains, warm-started from one retrain to the next: SPEC §3's
// network and the shipped recipe's objective BCE + β·|KL − C| (docs/training.md), with no
// curriculum, no latent stages and no masks: every training sees only the agent's own images.
//
// Guarantees: C at global iteration i (counted over all trainings of the run) is
// capacity_max · min(1, i / capacity_iters); Adam's state persists across trainings (warm
// start: same weights, same moments). Training number r draws its batches from
// Prng(seed, 1000 + r) uniformly with replacement over the images it is given, and its
// reparameterisation noise from torch::manual_seed(seed · 1000 + r), so a training depends
// only on the weights and Adam state it starts from, its images and r: a resumed run that
// loads the checkpoint of training r − 1 trains r exactly as an uninterrupted run (one thread).
//
// Progressive latents (options.progressive()): a training uses the first
// options.open_latents_at(C at its last iteration) latents; the others are held at the prior
// (zero read-out rows and decoder column, gradients masked every step, so they stay exactly
// zero and their KL is 0). Latents that open at a training get fresh read-out weights ×
// release_scale, drawn after that training's torch::manual_seed (so a resume draws the same).
//
// Anchoring (options.anchor_weight > 0, a progressive training that opens latents while
// others are open): μ and log σ² of the open latents under the model before the training are
// kept for every image, and each step adds anchor_weight · mean over the batch of
// Σ_l KL(N(μ_l, σ_l²) ‖ N(μ_l^before, σ_l^before²)) over those latents.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <torch/torch.h>

#include "host_tools/online/online_options.hpp"
#include "host_tools/vae/vae_model.hpp"

namespace curio::online {

struct TrainingStats {
  int64_t iterations = 0;
  double seconds = 0.0;
  double recon = 0.0;     // mean over the last 100 iterations (nats per image)
  double kl = 0.0;        // total KL, same window
  double capacity = 0.0;  // C at the last iteration
  int open_latents = 10;  // latents this training could use (progressive latents)
  int anchored = 0;              // latents anchored to their code before the training (0: none)
  double anchor_kl = 0.0;        // their KL to that code, mean over the last 100 iterations (nats)
};

// The indices of the k images with the largest reconstruction error, worst first (ties:
// lower index first); all of them when k ≥ errors.size(). Novelty steps explore around them.
std::vector<uint32_t> worst_reconstructed(const std::vector<double>& errors, size_t k);

class OnlineVae {
 public:
  // Seeded Kaiming init, enc.fc_out × out_init_scale (KL ≈ 0 at the start).
  explicit OnlineVae(const OnlineOptions& options);

  // `iterations` Adam steps of training number `round` on images_u8 (uint8 NCHW).
  // `progress(line)` gets a line every 500 iterations.
  TrainingStats train(const torch::Tensor& images_u8, int64_t iterations, int round,
                      const std::function<void(const std::string&)>& progress);

  // Checkpoint (weights, Adam state, global iteration) via train::save_checkpoint.
  void save(const std::string& path, int64_t images);
  void load(const std::string& path);

  train::Vae& model() { return model_; }
  int64_t iteration() const { return iteration_; }
  double capacity_at(int64_t iteration) const;
  // Latents not held at the prior (all 10 unless progressive).
  int open_latents() const;

 private:
  OnlineOptions o_;
  train::Vae model_;
  torch::optim::Adam optimizer_;
  int64_t iteration_ = 0;
  train::LatentMask held_{};  // read back from the weights after load()
};

}  // namespace curio::online
