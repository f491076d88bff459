// Running a trained model over a held-out scene set: latent means, per-latent KL,
// reconstruction, and the factor report.
#pragma once
#include <string>
#include <vector>

#include <torch/torch.h>

#include "host_tools/vae/factor_report.hpp"
#include "host_tools/vae/scene_set.hpp"
#include "host_tools/vae/vae_model.hpp"

namespace curio::train {

// Streams of curio::Prng used for each scene set, so held-out sets never repeat training images.
inline constexpr uint64_t kTrainStream = 7;
inline constexpr uint64_t kEvalStream = 8;    // in-training evaluation
inline constexpr uint64_t kReportStream = 9;  // `curio-train report`
inline constexpr uint64_t kKlStream = 10;     // KL profile for the exported meta (SPEC §2.4)

struct Encoded {
  torch::Tensor mu;      // [N,10]
  torch::Tensor logvar;  // [N,10]
  double recon = 0.0;    // mean BCE (nats per image) decoding z = μ; only if asked
  torch::Tensor recon_each;  // [N] float64: each image's BCE decoding μ; only if asked
};

// Encoder over all images in batches, no gradients (and the decoder when with_recon).
Encoded encode_all(Vae& model, const torch::Tensor& images_u8, bool with_recon = false);

// Mean KL per latent over the encoded images.
std::vector<double> mean_kl(const Encoded& e);

// Factor report of the model's μ on `set`; with `recon`, also the mean reconstruction
// (nats per image, decoding μ) stored there.
FactorReport evaluate_factors(Vae& model, const std::string& model_kind, const SceneSet& set,
                              const Criteria& criteria = {}, double* recon = nullptr);

// Columns of a [N,K] float tensor as doubles.
std::vector<std::vector<double>> columns(const torch::Tensor& t);

}  // namespace curio::train
