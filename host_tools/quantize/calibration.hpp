// The images the quantizer calibrates activation ranges on: SPEC §3's passive-phase
// distribution (ball and distractor independently uniform in [−1, 1]²), rendered by the
// simulator and turned into the camera's uint8 frames.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "firmware/nn/encoder_arch.hpp"

namespace curio::quantize {

using CameraFrame = std::vector<uint8_t>;  // 64×64×3 HWC

// What the camera sends for a rendered float image (HWC, [0,1]): round(255·v) in double,
// ties away from zero, clamped (as firmware/protocol's camera_pixel).
CameraFrame to_camera_frame(const float* image_hwc);
// The float image the encoder sees after the camera: p / 255.
std::vector<float> frame_to_float(const CameraFrame& frame);

// `count` rendered scenes from a PCG32 stream seeded with `seed`: per image ball (x, y)
// then distractor (x, y), each uniform in [−1, 1]. Float HWC images in [0, 1].
// factors (optional) receives each scene's ball x, ball y, distractor x, distractor y.
std::vector<std::vector<float>> render_scenes(int count, uint64_t seed,
                                              std::vector<std::array<float, 4>>* factors = nullptr);

}  // namespace curio::quantize
