#include "host_tools/train/scene_set.hpp"

#include <algorithm>
#include <cmath>
#include <thread>
#include <vector>

#include "firmware/explore/prng.hpp"
#include "sim/render.hpp"

namespace curio::train {

SceneSet render_scene_set(int64_t n, uint64_t seed, uint64_t stream, int threads,
                          double ball_spread) {
  SceneSet set;
  set.factors = torch::empty({n, 4}, torch::kFloat32);
  set.images = torch::empty({n, 3, sim::kImageSize, sim::kImageSize}, torch::kUInt8);
  float* f = set.factors.data_ptr<float>();
  Prng rng(seed, stream);
  for (int64_t i = 0; i < 4 * n; ++i) {
    const double spread = i % 4 < 2 ? ball_spread : 1.0;  // ball x, ball y, distractor x, y
    f[i] = static_cast<float>(spread * rng.uniform(-1.0, 1.0));
  }

  uint8_t* out = set.images.data_ptr<uint8_t>();
  constexpr int64_t kPlane = sim::kImageSize * sim::kImageSize;
  auto work = [&](int64_t begin, int64_t end) {
    sim::Image hwc;
    for (int64_t i = begin; i < end; ++i) {
      const float* p = f + 4 * i;
      sim::render_scene({p[0], p[1]}, {p[2], p[3]}, &hwc);
      uint8_t* img = out + i * 3 * kPlane;
      for (int64_t px = 0; px < kPlane; ++px)
        for (int64_t c = 0; c < 3; ++c) {
          const float v = std::clamp(hwc[static_cast<size_t>(px * 3 + c)], 0.0f, 1.0f);
          img[c * kPlane + px] = static_cast<uint8_t>(std::lround(v * 255.0f));
        }
    }
  };
  const int t = std::max(1, threads);
  std::vector<std::thread> pool;
  for (int k = 0; k < t; ++k) pool.emplace_back(work, n * k / t, n * (k + 1) / t);
  for (auto& th : pool) th.join();
  return set;
}

torch::Tensor to_float(const torch::Tensor& images_u8) {
  return images_u8.to(torch::kFloat32).div_(255.0);
}

torch::Tensor gather_images(const torch::Tensor& images_u8, const torch::Tensor& index) {
  return to_float(images_u8.index_select(0, index));
}

}  // namespace curio::train
