// The committed Cortex-M test vectors are current, and the host kernels reproduce them.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "firmware/nn/conv_s8.hpp"
#include "firmware/nn/fully_connected_s8.hpp"
#include "tests/nn/qemu/kernel_vectors.hpp"
#include "tests/nn/encoder_layer_reference.hpp"
#include "tests/nn/qemu_vectors.hpp"
#include "tests/nn/reference_kernels.hpp"

namespace curio::nn {
namespace {

TEST(QemuVectors, CommittedHeaderIsCurrent) {
  std::ifstream in(std::string(CURIO_SOURCE_DIR) + "/" + testing::kQemuVectorsPath,
                   std::ios::binary);
  ASSERT_TRUE(in) << "missing " << testing::kQemuVectorsPath;
  const std::string committed((std::istreambuf_iterator<char>(in)),
                              std::istreambuf_iterator<char>());
  EXPECT_TRUE(committed == testing::make_qemu_vectors_header())
      << testing::kQemuVectorsPath << " is stale; regenerate it with\n"
      << "  cmake --build <build> --target curio_nn_make_qemu_vectors && "
      << "<build>/tests/nn/curio_nn_make_qemu_vectors " << testing::kQemuVectorsPath;
}

TEST(EncoderLayers, CommittedHashesAreCurrent) {
  std::ifstream in(std::string(CURIO_SOURCE_DIR) + "/" + testing::kEncoderLayerHashesPath, std::ios::binary);
  ASSERT_TRUE(in) << "missing " << testing::kEncoderLayerHashesPath;
  const std::string committed((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_TRUE(committed == testing::make_encoder_layer_hashes_header())
      << testing::kEncoderLayerHashesPath << " is stale; regenerate it with\n"
      << "  cmake --build <build> --target curio_nn_make_encoder_layer_hashes && "
      << "<build>/tests/nn/curio_nn_make_encoder_layer_hashes " << testing::kEncoderLayerHashesPath;
}

TEST(QemuVectors, HostKernelsReproduceThem) {
  alignas(16) static int8_t scratch[64 * 1024];
  for (const auto& v : qemu_vectors::kConvVectors) {
    SCOPED_TRACE(v.name);
    std::vector<int8_t> out(static_cast<size_t>(v.expected_size));
    ASSERT_EQ(conv_s8({scratch, sizeof scratch}, v.params, {v.multiplier, v.shift}, v.input_dims,
                      v.input, v.filter_dims, v.filter, v.bias, v.output_dims, out.data()),
              Status::kOk);
    EXPECT_TRUE(ref::same_values(out.data(),
                                 std::vector<int8_t>(v.expected, v.expected + v.expected_size)));
  }
  for (const auto& v : qemu_vectors::kFcVectors) {
    SCOPED_TRACE(v.name);
    if (v.s32) {
      std::vector<int32_t> out(static_cast<size_t>(v.expected_size));
      if (v.filter_w16 != nullptr) {
        ASSERT_EQ(fully_connected_s8_w16_s32({scratch, sizeof scratch}, v.params.input_offset,
                                             v.dims, v.input, v.filter_w16, v.bias, out.data()),
                  Status::kOk);
      } else {
        ASSERT_EQ(fully_connected_s8_s32({scratch, sizeof scratch}, v.params.input_offset, v.dims,
                                         v.input, v.filter, v.bias, out.data()),
                  Status::kOk);
      }
      EXPECT_TRUE(ref::same_values(
          out.data(), std::vector<int32_t>(v.expected_s32, v.expected_s32 + v.expected_size)));
    } else {
      std::vector<int8_t> out(static_cast<size_t>(v.expected_size));
      ASSERT_EQ(fully_connected_s8({scratch, sizeof scratch}, v.params, {v.multiplier, v.shift},
                                   v.dims, v.input, v.filter, v.bias, out.data()),
                Status::kOk);
      EXPECT_TRUE(ref::same_values(
          out.data(), std::vector<int8_t>(v.expected_s8, v.expected_s8 + v.expected_size)));
    }
  }
}

}  // namespace
}  // namespace curio::nn
