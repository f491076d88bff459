// The encoder of SPEC §3 as compile-time constants: 4 × [conv 32 ch, 4×4, stride 2, pad 1,
// ReLU] (64→32→16→8→4), flatten 512 (NHWC here), FC 256 ReLU, FC 256 ReLU, FC 20
// (μ and log-variance of 10 latents).
#pragma once
#include <cstdint>

namespace curio::nn {

inline constexpr int32_t kImageSize = 64;
inline constexpr int32_t kImageChannels = 3;
inline constexpr int32_t kImageBytes = kImageSize * kImageSize * kImageChannels;
inline constexpr int32_t kConvLayers = 4;
inline constexpr int32_t kConvChannels = 32;
inline constexpr int32_t kKernelSize = 4;
inline constexpr int32_t kConvStride = 2;
inline constexpr int32_t kConvPad = 1;
inline constexpr int32_t kHidden = 256;
inline constexpr int32_t kLatents = 10;

// Side of the map layer `i` reads (i = 0: the image) and of the map it writes (i + 1).
constexpr int32_t conv_map_size(int32_t i) {
  return kImageSize >> i;
}
constexpr int32_t conv_input_channels(int32_t i) {
  return i == 0 ? kImageChannels : kConvChannels;
}
constexpr int32_t conv_filter_values(int32_t i) {
  return kConvChannels * kKernelSize * kKernelSize * conv_input_channels(i);
}

inline constexpr int32_t kFinalMapSize = conv_map_size(kConvLayers);
inline constexpr int32_t kFlatten = kFinalMapSize * kFinalMapSize * kConvChannels;

static_assert(kFinalMapSize == 4 && kFlatten == 512, "SPEC §3: the last conv map is 4×4×32");
static_assert((conv_map_size(0) + 2 * kConvPad - kKernelSize) / kConvStride + 1 == conv_map_size(1),
              "4×4 stride-2 pad-1 convolutions halve the map");

}  // namespace curio::nn
