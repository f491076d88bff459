#include "quantize/calibration.hpp"

#include <cmath>

#include "explore/prng.hpp"
#include "sim/render.hpp"

namespace curio::quantize {

static_assert(sim::kImageValues == nn::kImageBytes, "renderer and encoder agree on the image");

CameraFrame to_camera_frame(const float* image_hwc) {
  CameraFrame f(static_cast<size_t>(nn::kImageBytes));
  for (size_t i = 0; i < f.size(); ++i) {
    // Same as the camera node's protocol::camera_pixel: in double, NaN → 0.
    const double v = image_hwc[i];
    f[i] = !(v > 0.0) ? uint8_t{0}
           : v >= 1.0 ? uint8_t{255}
                      : static_cast<uint8_t>(std::round(v * 255.0));
  }
  return f;
}

std::vector<float> frame_to_float(const CameraFrame& frame) {
  std::vector<float> v(frame.size());
  for (size_t i = 0; i < v.size(); ++i) v[i] = static_cast<float>(frame[i]) / 255.0f;
  return v;
}

std::vector<std::vector<float>> render_scenes(int count, uint64_t seed) {
  Prng rng(seed);
  std::vector<std::vector<float>> images;
  images.reserve(static_cast<size_t>(count));
  sim::Image image{};
  for (int i = 0; i < count; ++i) {
    sim::Vec2 ball, distractor;
    ball.x = rng.uniform(-1.0, 1.0);
    ball.y = rng.uniform(-1.0, 1.0);
    distractor.x = rng.uniform(-1.0, 1.0);
    distractor.y = rng.uniform(-1.0, 1.0);
    sim::render_scene(ball, distractor, &image);
    images.emplace_back(image.begin(), image.end());
  }
  return images;
}

}  // namespace curio::quantize
