// A user's image as the camera frame the controller encodes: an 8-bit RGB PNG of 64×64
// (what the arm's camera sends, row 0 at the top, HWC bytes). Other sizes are refused, or
// resampled when asked: per axis, an area average (box filter) when shrinking and linear
// interpolation between pixel centres when enlarging, each output byte rounded.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "firmware/nn/encoder_arch.hpp"

namespace curio::encode {

using CameraFrame = std::array<uint8_t, nn::kImageBytes>;

struct CameraImage {
  std::string path;
  CameraFrame frame{};
  int source_width = 0;   // the PNG's own size
  int source_height = 0;
  bool resized = false;
};

// Reads `path` into *out. Returns "" on success, else one line naming the file and what is
// wrong with it (not a PNG, truncated or corrupt, greyscale, 16-bit, an alpha channel, or
// not 64×64 without `resize`). Palette PNGs are expanded to their RGB colours.
std::string read_camera_png(const std::string& path, bool resize, CameraImage* out);

// Resamples an 8-bit HWC RGB image to 64×64 as read_camera_png does (exposed for tests).
CameraFrame resample_to_camera(const std::vector<uint8_t>& rgb, int width, int height);

}  // namespace curio::encode
