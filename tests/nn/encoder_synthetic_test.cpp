// The int8 encoder on a random Kaiming-initialised model: close to the float reference,
// deterministic, and failing loudly (status + fault counter) on a broken model.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "host_tools/model_io/float_encoder.hpp"
#include "firmware/nn/encoder.hpp"
#include "host_tools/quantize/calibration.hpp"
#include "host_tools/quantize/encoder_quantizer.hpp"
#include "host_tools/quantize/evaluation.hpp"
#include "tests/nn/synthetic_model.hpp"

namespace curio::nn {
namespace {

struct SyntheticSetup {
  model_io::FloatModel model;
  std::unique_ptr<model_io::FloatEncoder> float_encoder;
  quantize::QuantizedEncoder quantized;
};

const SyntheticSetup& setup() {
  static const SyntheticSetup* s = [] {
    auto* p = new SyntheticSetup;
    p->model.tensors = testing::synthetic_encoder_tensors(5);
    p->float_encoder = std::make_unique<model_io::FloatEncoder>(p->model);
    std::vector<quantize::CameraFrame> frames;
    for (const auto& image : quantize::render_scenes(300, 1)) {
      frames.push_back(quantize::to_camera_frame(image.data()));
    }
    p->quantized = quantize::quantize_calibrated(p->model, *p->float_encoder, frames,
                                                 quantize::ActivationScales::kPerTensor);
    return p;
  }();
  return *s;
}

TEST(EncoderSynthetic, Int8MuTracksTheFloatReference) {
  const auto images = quantize::render_scenes(300, 2);  // other scenes than calibration
  const quantize::Int8VsFloat r =
      quantize::compare_int8_to_float(*setup().float_encoder, setup().quantized.model(), images);
  ASSERT_EQ(r.encoder_faults, 0);
  ASSERT_EQ(r.images, 300);
  // Error relative to μ's size (a random model's μ barely varies between images, so its
  // spread is no yardstick): each of the six int8 activation tensors adds rounding noise of
  // step/√12 with step = range/255, ≈ 1 % of the tensor's RMS when the range is ~10× the
  // RMS; six such layers compound to a few percent. 6 % is that bound; a layout, offset
  // or rescale bug gives errors of the order of μ itself.
  double sum_mu2 = 0.0, max_mu = 0.0;
  for (const auto& image : images) {
    for (float m : setup().float_encoder->mu(image.data())) {
      sum_mu2 += static_cast<double>(m) * m;
      max_mu = std::max(max_mu, std::abs(static_cast<double>(m)));
    }
  }
  const double rms_mu = std::sqrt(sum_mu2 / (images.size() * kLatents));
  std::printf("synthetic model: max|dmu| %.5f  mean|dmu| %.6f  rms|mu| %.4f  max|mu| %.4f\n",
              r.max_abs_mu_error, r.mean_abs_mu_error, rms_mu, max_mu);
  EXPECT_LT(r.mean_abs_mu_error, 0.06 * rms_mu);
  EXPECT_LT(r.max_abs_mu_error, 0.06 * max_mu);
}

TEST(EncoderSynthetic, SameImageSameMu) {
  auto encoder = std::make_unique<Encoder>(setup().quantized.model());
  const auto image = quantize::render_scenes(1, 9)[0];
  const auto frame = quantize::to_camera_frame(image.data());
  float a[kLatents], b[kLatents], lv[kLatents];
  ASSERT_EQ(encoder->encode(frame.data(), a), Status::kOk);
  ASSERT_EQ(encoder->encode(frame.data(), b, lv), Status::kOk);
  for (size_t j = 0; j < kLatents; ++j) EXPECT_EQ(a[j], b[j]);
  EXPECT_EQ(encoder->encodes(), 2u);
  EXPECT_EQ(encoder->faults(), 0u);
}

TEST(EncoderSynthetic, BrokenModelIsReportedAndCounted) {
  EncoderModel broken = setup().quantized.model();
  broken.conv[2].filter = nullptr;
  auto encoder = std::make_unique<Encoder>(broken);
  std::vector<uint8_t> frame(kImageBytes, 0);
  float mu[kLatents] = {42.0f};
  EXPECT_EQ(encoder->encode(frame.data(), mu), Status::kArgumentError);
  EXPECT_EQ(mu[0], 42.0f);
  EXPECT_EQ(encoder->encode(nullptr, mu), Status::kArgumentError);
  EXPECT_EQ(encoder->faults(), 2u);
  EXPECT_EQ(encoder->encodes(), 0u);
}

TEST(EncoderSynthetic, QuantizerPermutesFc1ColumnsToNhwc) {
  // fc1 column for NCHW index c·16 + h·4 + w must sit at NHWC index (h·4 + w)·32 + c.
  const auto& w = setup().model.find("enc.fc1.weight")->data;
  const auto& q = setup().quantized.fc1;
  for (int o : {0, 77, 255}) {
    for (int c : {0, 5, 31}) {
      for (int hw : {0, 6, 15}) {
        const float real = w[static_cast<size_t>(o * kFlatten + c * 16 + hw)];
        const int8_t got = q.filter[static_cast<size_t>(o * kFlatten + hw * 32 + c)];
        // The input channel's scale is folded into the weight before quantization.
        EXPECT_NEAR(got * q.acc_scale[static_cast<size_t>(o)],
                    real * q.input.scale_of(static_cast<size_t>(c)),
                    0.5 * q.acc_scale[static_cast<size_t>(o)] + 1e-9);
      }
    }
  }
}

}  // namespace
}  // namespace curio::nn
