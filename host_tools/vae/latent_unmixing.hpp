// Unsupervised re-alignment of a trained model's active latents: whitening plus FastICA
// (Hyvärinen 1999, symmetric, log-cosh contrast) on the encoder means μ of training images,
// written back into the network as an exact linear reparameterisation of the μ path
// (enc.fc_out's μ rows and dec.fc1's columns), so the decoder still reconstructs μ's images
// exactly. Uses images only, never the factor labels.
//
// Why: a β-VAE pruned from a wider code keeps both objects in four latents that each mix them
// (docs/training.md, trials h4/h5); the β-VAE objective does not rotate them onto the
// factors in tens of thousands of iterations. The scene factors are independent and uniform
// (strongly non-Gaussian), which is exactly what ICA recovers from a linear mixture.
#pragma once
#include <cstdint>
#include <vector>

#include <torch/torch.h>

#include "host_tools/vae/vae_model.hpp"

namespace curio::train {

struct FastIcaResult {
  torch::Tensor unmixing;  // [k,k] orthogonal W: sources = whitened · Wᵀ
  int iterations = 0;
  bool converged = false;
};

// Symmetric FastICA on whitened data [N,k] (zero mean, identity covariance), float64.
// Deterministic: starts from a random orthogonal matrix drawn from `seed`.
FastIcaResult fast_ica(const torch::Tensor& whitened, uint64_t seed, int max_iterations = 500,
                       double tolerance = 1e-10);

struct UnmixResult {
  std::vector<int> active;              // latents unmixed (mean KL > active_kl), in index order
  torch::Tensor transform;              // [k,k] A: new μ = A (μ − mean)
  torch::Tensor mean;                   // [k]
  std::vector<double> excess_kurtosis;  // of each new latent (uniform sources: −1.2)
  FastIcaResult ica;
};

// Unmixes the active latents of `model` in place, from its μ on `images_u8` (uint8 NCHW).
// Throws std::runtime_error when fewer than two latents are active.
UnmixResult unmix_active_latents(Vae& model, const torch::Tensor& images_u8, uint64_t seed,
                                 double active_kl = 0.5);

}  // namespace curio::train
