// The emitted header is the quantizer's result: same integers as the in-memory
// quantization, same μ bit for bit.
#include <gtest/gtest.h>

#include <memory>

#include "host_tools/model_io/float_encoder.hpp"
#include "firmware/nn/encoder.hpp"
#include "host_tools/quantize/calibration.hpp"
#include "host_tools/quantize/encoder_quantizer.hpp"
#include "tests/nn/synthetic_firmware_model.hpp"
#include "tests/nn/synthetic_model.hpp"

namespace curio::nn {
namespace {

template <typename T>
::testing::AssertionResult same_array(const char* what, const T* got, const std::vector<T>& want) {
  for (size_t i = 0; i < want.size(); ++i) {
    if (got[i] != want[i]) {
      return ::testing::AssertionFailure() << what << " first mismatch at " << i << ": header "
                                           << +got[i] << ", in memory " << +want[i];
    }
  }
  return ::testing::AssertionSuccess();
}

void expect_layer(const char* name, const QuantizedLayer& h, const quantize::HostLayer& m) {
  SCOPED_TRACE(name);
  EXPECT_TRUE(same_array("filter", h.filter, m.filter));
  EXPECT_TRUE(same_array("bias", h.bias, m.bias));
  EXPECT_TRUE(same_array("multiplier", h.multiplier, m.multiplier));
  EXPECT_TRUE(same_array("shift", h.shift, m.shift));
  EXPECT_EQ(h.input_offset, -m.input.zero_point);
  EXPECT_EQ(h.output_offset, m.output.zero_point);
}

TEST(EncoderHeader, MatchesInMemoryQuantization) {
  model_io::FloatModel model{testing::synthetic_encoder_tensors(testing::kSyntheticSeed)};
  const model_io::FloatEncoder float_encoder(model);
  std::vector<quantize::CameraFrame> frames;
  for (const auto& image : quantize::render_scenes(testing::kSyntheticCalibrationImages,
                                                   testing::kSyntheticCalibrationSeed)) {
    frames.push_back(quantize::to_camera_frame(image.data()));
  }
  const quantize::QuantizedEncoder q = quantize::quantize_calibrated(
      model, float_encoder, frames, quantize::ActivationScales::kPerTensor);
  const EncoderModel& h = testing::synthetic_firmware_model();
  for (size_t i = 0; i < kConvLayers; ++i) expect_layer("conv", h.conv[i], q.conv[i]);
  expect_layer("fc1", h.fc1, q.fc1);
  expect_layer("fc2", h.fc2, q.fc2);
  EXPECT_TRUE(same_array("latent filter", h.latent.filter, q.latent.filter));
  EXPECT_TRUE(same_array("latent bias", h.latent.bias, q.latent.bias));
  EXPECT_TRUE(same_array("latent scale", h.latent.scale, q.latent.scale));

  auto from_header = std::make_unique<Encoder>(h);
  auto from_memory = std::make_unique<Encoder>(q.model());
  for (const auto& image : quantize::render_scenes(20, 77)) {
    const auto frame = quantize::to_camera_frame(image.data());
    float a[kLatents], b[kLatents];
    ASSERT_EQ(from_header->encode(frame.data(), a), Status::kOk);
    ASSERT_EQ(from_memory->encode(frame.data(), b), Status::kOk);
    for (size_t j = 0; j < kLatents; ++j) EXPECT_EQ(a[j], b[j]);
  }
}

TEST(EncoderHeader, CarriesTheMetaKlOrder) {
  const auto meta = testing::synthetic_meta(testing::kSyntheticSeed);
  for (size_t i = 0; i < kLatents; ++i)
    EXPECT_EQ(testing::synthetic_kl_order()[i], meta.kl_order[i]);
}

}  // namespace
}  // namespace curio::nn
