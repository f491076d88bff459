// The points of the training loop where a recorded trial (trial_hooks.hpp) steps in, and the
// state of the run it may change there. The shipped recipe runs with no hooks.
#pragma once
#include <array>
#include <cstdint>

#include <torch/torch.h>

#include "host_tools/vae/recipe.hpp"
#include "host_tools/vae/vae_model.hpp"

namespace curio::train {

// What a run trains and what it has learnt about its latents so far.
struct TrainingState {
  const Recipe& recipe;
  Vae& model;
  torch::optim::Adam& optimizer;
  LatentMask& held;                      // latents held at the prior (latent stages)
  std::array<double, kLatents>& kl_ema;  // recent KL of each latent (~50 iterations)
};

// Each call happens once per run or iteration, in this order; every default does nothing.
class TrainingHook {
 public:
  virtual ~TrainingHook() = default;
  // Before the first iteration (`start` > 0 on resume); kl_ema holds the initial model's KL
  // in a fresh --init-from run. May throw std::runtime_error on options the run cannot honour.
  virtual void on_start(TrainingState&, int64_t /*start*/) {}
  // First thing in an iteration, before its schedule and batch.
  virtual void on_iteration_start(TrainingState&, int64_t /*it*/) {}
  // With the iteration's batch x, before the latent stage is applied.
  virtual void before_latent_stage(TrainingState&, int64_t /*it*/, const torch::Tensor& /*x*/) {}
  // When a latent stage is about to hold latents: fills `importance` (the latents of least
  // importance are held) and returns true to replace the recent KL as the measure.
  virtual bool pruning_importance(TrainingState&, const torch::Tensor& /*x*/,
                                  std::array<double, kLatents>& /*importance*/) {
    return false;
  }
  // After backward (and the held latents' gradient mask), before the optimiser step.
  virtual void after_backward(TrainingState&, int64_t /*it*/) {}
  // After the optimiser step.
  virtual void after_step(TrainingState&, int64_t /*it*/, const torch::Tensor& /*x*/) {}
};

// Drops Adam's moments of a module's parameters: re-initialised weights start afresh.
inline void forget_adam_state(torch::optim::Adam& optimizer, torch::nn::Module& module) {
  for (const auto& p : module.parameters())
    optimizer.state().erase(c10::guts::to_string(p.unsafeGetTensorImpl()));
}

}  // namespace curio::train
