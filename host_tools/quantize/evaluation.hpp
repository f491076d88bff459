// How far the int8 encoder is from the float model on rendered images: the numbers the
// acceptance criterion (max |Δμ| ≤ 0.05, same KL order) is judged on.
#pragma once
#include <array>
#include <vector>

#include "host_tools/model_io/float_encoder.hpp"
#include "firmware/nn/encoder_model.hpp"

namespace curio::quantize {

struct Int8VsFloat {
  int images = 0;
  double max_abs_mu_error = 0.0;  // over images and latents
  double mean_abs_mu_error = 0.0;
  std::array<double, nn::kLatents> max_abs_mu_error_per_latent{};
  // SPEC §2.4's per-latent KL to N(0,1), averaged over the images, from each encoder.
  std::array<double, nn::kLatents> kl_float{};
  std::array<double, nn::kLatents> kl_int8{};
  int encoder_faults = 0;
};

// Float images (HWC, [0,1]) go to the float encoder as they are and to the int8 encoder
// as camera frames (round(255·v)), so the camera's rounding is part of the error.
Int8VsFloat compare_int8_to_float(const model_io::FloatEncoder& float_encoder,
                                  const nn::EncoderModel& int8_model,
                                  const std::vector<std::vector<float>>& images);

// True when `a` and `b` order the latents the same way, ignoring swaps between latents
// whose KLs (in `reference`) differ by less than `tie_nats` (e.g. collapsed latents).
bool same_kl_order(const std::array<double, nn::kLatents>& reference,
                   const std::array<double, nn::kLatents>& other, double tie_nats);

}  // namespace curio::quantize
