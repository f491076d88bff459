#include "host_tools/quantize/evaluation.hpp"

#include <cmath>
#include <memory>

#include "firmware/nn/encoder.hpp"
#include "host_tools/quantize/calibration.hpp"

namespace curio::quantize {
namespace {

double kl_term(double mu, double log_var) {
  return 0.5 * (mu * mu + std::exp(log_var) - log_var - 1.0);
}

}  // namespace

Int8VsFloat compare_int8_to_float(const model_io::FloatEncoder& float_encoder,
                                  const nn::EncoderModel& int8_model,
                                  const std::vector<std::vector<float>>& images) {
  Int8VsFloat r;
  auto encoder = std::make_unique<nn::Encoder>(int8_model);  // 46 KiB arena: keep off the stack
  model_io::EncoderTrace trace;
  double sum_abs = 0.0;
  for (const auto& image : images) {
    float_encoder.forward(image.data(), &trace);
    const CameraFrame frame = to_camera_frame(image.data());
    float mu[nn::kLatents];
    float log_var[nn::kLatents];
    if (encoder->encode(frame.data(), mu, log_var) != nn::Status::kOk) {
      ++r.encoder_faults;
      continue;
    }
    for (size_t j = 0; j < nn::kLatents; ++j) {
      const double err = std::abs(static_cast<double>(mu[j]) - trace.out[j]);
      r.max_abs_mu_error_per_latent[j] = std::max(r.max_abs_mu_error_per_latent[j], err);
      r.max_abs_mu_error = std::max(r.max_abs_mu_error, err);
      sum_abs += err;
      r.kl_float[j] += kl_term(trace.out[j], trace.out[nn::kLatents + j]);
      r.kl_int8[j] += kl_term(mu[j], log_var[j]);
    }
    ++r.images;
  }
  if (r.images > 0) {
    r.mean_abs_mu_error = sum_abs / (r.images * nn::kLatents);
    for (size_t j = 0; j < nn::kLatents; ++j) {
      r.kl_float[j] /= r.images;
      r.kl_int8[j] /= r.images;
    }
  }
  return r;
}

bool same_kl_order(const std::array<double, nn::kLatents>& reference,
                   const std::array<double, nn::kLatents>& other, double tie_nats) {
  // Every pair the reference orders decisively must be ordered the same way by `other`.
  for (size_t a = 0; a < nn::kLatents; ++a) {
    for (size_t b = 0; b < nn::kLatents; ++b) {
      if (reference[a] - reference[b] >= tie_nats && !(other[a] > other[b])) return false;
    }
  }
  return true;
}

}  // namespace curio::quantize
