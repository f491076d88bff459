// The camera: what a rendered observation becomes on the wire and at the encoder's input,
// 64×64×3 uint8 HWC, each value protocol::camera_pixel(v) (round half away from zero of
// 255·v, clamped). The camera node, curio-lab and the quantizer all go through this one
// function, so the in-process and the over-CAN paths see the same bytes.
#pragma once
#include <array>
#include <cstdint>

#include "firmware/protocol/arm_messages.hpp"
#include "sim/render.hpp"

namespace curio::sim {

static_assert(kImageValues == static_cast<int>(protocol::kCameraImageBytes),
              "renderer and camera agree on the frame size");

using CameraFrame = std::array<uint8_t, kImageValues>;

inline void to_camera_frame(const float* image_hwc, uint8_t* frame) {
  for (int i = 0; i < kImageValues; ++i) frame[i] = protocol::camera_pixel(image_hwc[i]);
}

inline void to_camera_frame(const Image& image, CameraFrame* frame) {
  to_camera_frame(image.data(), frame->data());
}

}  // namespace curio::sim
