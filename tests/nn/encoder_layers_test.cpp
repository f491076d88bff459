// Every layer of the shipped β-VAE encoder, on this build's kernel path, equals the reference
// kernels' output bit for bit (by the per-layer checksums the Cortex-M7 image checks too,
// tests/nn/qemu/encoder_layer_hashes.hpp). Compiled into each kernel path's test binary.
#include <gtest/gtest.h>

#include <memory>

#include "firmware/nn/models/beta_vae_weights.hpp"
#include "tests/nn/qemu/encoder_layer_hashes.hpp"
#include "tests/nn/encoder_layer_hash.hpp"

namespace curio::nn {
namespace {

TEST(EncoderLayers, ThisPathReproducesEveryLayerOfTheReference) {
  auto encoder = std::make_unique<Encoder>(beta_vae::kEncoderModel);
  uint8_t frame[kImageBytes];
  testing::layer_test_frame(frame);
  testing::LayerHashes got;
  ASSERT_EQ(testing::hash_encoder_layers(*encoder, frame, &got), Status::kOk);
  const char* names[testing::kHashedLayers] = {"conv0", "conv1", "conv2", "conv3", "fc1", "fc2", "latent sums"};
  for (int32_t l = 0; l < testing::kHashedLayers; ++l)
    EXPECT_EQ(got.hash[l], testing::kBetaVaeLayerHashes[l]) << names[l] << " on path " << simd_path();
  // A second encode (filters already prepared) gives the same layers.
  testing::LayerHashes again;
  ASSERT_EQ(testing::hash_encoder_layers(*encoder, frame, &again), Status::kOk);
  for (int32_t l = 0; l < testing::kHashedLayers; ++l) EXPECT_EQ(again.hash[l], got.hash[l]) << l;
}

}  // namespace
}  // namespace curio::nn
