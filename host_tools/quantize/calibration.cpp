#include "host_tools/quantize/calibration.hpp"

#include <cmath>

#include "firmware/explore/prng.hpp"
#include "sim/camera.hpp"
#include "sim/render.hpp"

namespace curio::quantize {

static_assert(sim::kImageValues == nn::kImageBytes, "renderer and encoder agree on the image");

CameraFrame to_camera_frame(const float* image_hwc) {
  CameraFrame f(static_cast<size_t>(nn::kImageBytes));
  sim::to_camera_frame(image_hwc, f.data());  // exactly what the camera node sends
  return f;
}

std::vector<float> frame_to_float(const CameraFrame& frame) {
  std::vector<float> v(frame.size());
  for (size_t i = 0; i < v.size(); ++i) v[i] = static_cast<float>(frame[i]) / 255.0f;
  return v;
}

std::vector<std::vector<float>> render_scenes(int count, uint64_t seed,
                                              std::vector<std::array<float, 4>>* factors) {
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
    if (factors)
      factors->push_back({static_cast<float>(ball.x), static_cast<float>(ball.y),
                          static_cast<float>(distractor.x), static_cast<float>(distractor.y)});
    images.emplace_back(image.begin(), image.end());
  }
  return images;
}

}  // namespace curio::quantize
