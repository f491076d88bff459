// The camera: what a rendered observation becomes on the wire and at the encoder's input,
// 64×64×3 uint8 HWC, value = round(255·v) with v clamped to [0, 1].
#pragma once
#include <array>
#include <cmath>
#include <cstdint>

#include "sim/render.hpp"

namespace curio::sim {

using CameraFrame = std::array<uint8_t, kImageValues>;

inline void to_camera_frame(const Image& image, CameraFrame* frame) {
  for (int i = 0; i < kImageValues; ++i) {
    const float v = image[static_cast<size_t>(i)];
    const float c = v < 0.0f ? 0.0f : (v > 1.0f ? 1.0f : v);
    (*frame)[static_cast<size_t>(i)] = static_cast<uint8_t>(std::lround(c * 255.0f));
  }
}

}  // namespace curio::sim
