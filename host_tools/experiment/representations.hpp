// Learned goal spaces (SPEC §2.4, §3): the int8 encoders whose generated weight headers are
// compiled into this build (firmware/nn/models/<name>_weights.hpp), with the latents' KL order.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "firmware/nn/encoder_model.hpp"

namespace curio::lab {

struct Representation {
  std::string name;                    // "beta_vae", "vae"
  const nn::EncoderModel* model;       // int8 weights, as the controller runs them
  std::array<uint8_t, 10> kl_order;    // latent indices by decreasing KL (SPEC §2.4)
  std::array<float, 10> kl_per_latent;
  std::string inputs_sha256;           // provenance of the weights
};

// nullptr when that model's weight header was not present at build time.
const Representation* find_representation(const std::string& name);
std::vector<std::string> available_representations();

// The latents encoding the ball (best |corr| with ball x or ball y, active), read from the
// trainer's factor report beside the weights (firmware/nn/models/<name>.factor_report.json);
// empty when there is no report.
std::vector<int> ball_latents(const std::string& name);

}  // namespace curio::lab
