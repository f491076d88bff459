// Checkpoints: one torch archive holding the model, the Adam state, the iteration, the
// default CPU generator state (reparameterisation noise) and the recipe, so a killed
// training resumes exactly where its last checkpoint left it.
//
// Verified: "<path>.crc" beside it holds the CRC-32 and size of the file (LibTorch's reader
// does not check its zip CRCs: a damaged archive loads as NaN weights). load_checkpoint refuses
// a file whose CRC or size is not recorded there. Saving writes the new entry beside the old
// one first, renames the archive into place, then keeps the new entry only: a kill at any point
// leaves an archive that its .crc file vouches for. A checkpoint without a .crc file (an older
// curio-train wrote it) loads unverified (CheckpointInfo::verified false).
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
  bool verified = false;  // its CRC-32 and size matched "<path>.crc"
};

// Writes `path` atomically (temporary file, then rename).
void save_checkpoint(const std::string& path, Vae& model, torch::optim::Adam& optimizer,
                     const Recipe& recipe, int64_t iteration);

// Loads into `model` (and `optimizer` and the generator state when `optimizer` is given).
// Throws std::runtime_error naming the file when it is missing, unreadable or damaged (its
// CRC-32 is not the one recorded beside it); then nothing was loaded.
CheckpointInfo load_checkpoint(const std::string& path, Vae& model,
                               torch::optim::Adam* optimizer);

// "<dir>/checkpoint.pt".
std::string checkpoint_path(const std::string& dir);

// "<path>.crc": the CRC-32 and size of the checkpoint at `path`.
std::string checkpoint_crc_path(const std::string& path);

}  // namespace curio::train
