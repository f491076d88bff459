// The training figures: per-latent KL over training (gnuplot PNG from the CSV), the
// latent traversal (SPEC §4) and originals against reconstructions.
#pragma once
#include <string>
#include <vector>

#include <torch/torch.h>

#include "host_tools/vae/vae_model.hpp"

namespace curio::train {

// training.csv (columns iteration,…,kl_z0…kl_z9) → PNG with one line per latent.
// Returns false with a message in *error (e.g. gnuplot missing).
bool write_kl_plot(const std::string& csv_path, const std::string& png_path, std::string* error);

// One row per latent in `order` (decreasing KL): column 0 the image itself, then the decoded
// image with that latent set to 10 values evenly over [−3, 3] and the others at μ.
// image: float [3,64,64] in [0,1].
bool write_traversal_png(Vae& model, const torch::Tensor& image, const std::vector<int>& order,
                         const std::string& png_path, std::string* error);

// Top row the images, bottom row sigmoid(decoder(μ)). images: float [K,3,64,64].
bool write_reconstruction_png(Vae& model, const torch::Tensor& images, const std::string& png_path,
                              std::string* error);

}  // namespace curio::train
