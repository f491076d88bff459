// Checkpoints: one torch archive holding the model, the Adam state, the iteration, the
// default CPU generator state (reparameterisation noise) and the recipe, so a killed
// training resumes exactly where its last checkpoint left it.
#pragma once
#include <cstdint>
#include <string>

#include <torch/torch.h>

#include "host_tools/vae/recipe.hpp"
#include "host_tools/vae/vae_model.hpp"

namespace curio::train {

struct CheckpointInfo {
  Recipe recipe;
  int64_t iteration = 0;  // iterations completed
};

// Writes `path` atomically (temporary file, then rename).
void save_checkpoint(const std::string& path, Vae& model, torch::optim::Adam& optimizer,
                     const Recipe& recipe, int64_t iteration);

// Loads into `model` (and `optimizer` and the generator state when `optimizer` is given).
// Throws std::runtime_error naming the file when it is missing or unreadable.
CheckpointInfo load_checkpoint(const std::string& path, Vae& model,
                               torch::optim::Adam* optimizer);

// "<dir>/checkpoint.pt".
std::string checkpoint_path(const std::string& dir);

}  // namespace curio::train
