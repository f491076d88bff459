// The encoder of SPEC §3 as the float model file names it: 4 × conv(32, 4×4, s2, p1) + ReLU
// (64→32→16→8→4), flatten (PyTorch NCHW order: c*16 + h*4 + w), FC 512→256 ReLU,
// FC 256→256 ReLU, FC 256→20 (rows 0–9 μ, rows 10–19 log-variance).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace curio::model_io {

inline constexpr int kImageSize = 64;
inline constexpr int kImageChannels = 3;
inline constexpr int kConvLayers = 4;
inline constexpr int kConvChannels = 32;
inline constexpr int kKernel = 4;
inline constexpr int kStride = 2;
inline constexpr int kPad = 1;
inline constexpr int kFinalMapSize = 4;                                         // 64 / 2^4
inline constexpr int kFlatten = kConvChannels * kFinalMapSize * kFinalMapSize;  // 512
inline constexpr int kHidden = 256;
inline constexpr int kLatents = 10;
inline constexpr int kEncoderOutputs = 2 * kLatents;  // μ then log-variance

struct TensorSpec {
  std::string name;
  std::vector<int64_t> dims;
};

// The 14 encoder tensors in file order: conv0..3 weight/bias, fc1, fc2, fc_out weight/bias.
const std::vector<TensorSpec>& encoder_tensor_specs();

struct FloatModel;
// Throws ModelFormatError if any encoder tensor is missing or has the wrong shape, or holds
// a non-finite value.
void validate_encoder(const FloatModel& model);

}  // namespace curio::model_io
