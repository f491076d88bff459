#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "sim/render.hpp"

namespace curio::sim {

bool write_png(const std::string& path, const float* hwc, int width, int height,
               std::string* error) {
  if (width <= 0 || height <= 0) {
    if (error) *error = "image size must be positive";
    return false;
  }
  const size_t count = static_cast<size_t>(width) * static_cast<size_t>(height) * 3;
  std::vector<uint8_t> bytes(count);
  for (size_t i = 0; i < count; ++i) {
    const float v = std::isnan(hwc[i]) ? 0.0f : std::clamp(hwc[i], 0.0f, 1.0f);
    bytes[i] = static_cast<uint8_t>(std::lround(v * 255.0f));
  }
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(width);
  image.height = static_cast<png_uint_32>(height);
  image.format = PNG_FORMAT_RGB;
  if (!png_image_write_to_file(&image, path.c_str(), 0, bytes.data(), 0, nullptr)) {
    if (error) *error = "cannot write PNG '" + path + "': " + image.message;
    png_image_free(&image);
    return false;
  }
  return true;
}

}  // namespace curio::sim
