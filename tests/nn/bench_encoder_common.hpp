// What both encoder benchmarks share: one rendered scene as a camera frame and as a float
// image, and the int8 encoder benchmark itself.
#pragma once
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "firmware/nn/encoder.hpp"
#include "host_tools/quantize/calibration.hpp"
#include "sim/render.hpp"
#include "tests/nn/synthetic_firmware_model.hpp"

namespace curio::nn::bench {

// Ball at (0.3, −0.2), distractor at (−0.5, 0.4): a typical frame.
inline const std::vector<float>& scene_image() {
  static const std::vector<float> image = [] {
    sim::Image img{};
    sim::render_scene({0.3, -0.2}, {-0.5, 0.4}, &img);
    return std::vector<float>(img.begin(), img.end());
  }();
  return image;
}

inline const quantize::CameraFrame& scene_frame() {
  static const quantize::CameraFrame frame = quantize::to_camera_frame(scene_image().data());
  return frame;
}

// One image per iteration on the calling thread (the controller's single core).
inline void BM_Int8Encoder(benchmark::State& state) {
  static Encoder encoder(testing::synthetic_firmware_model());
  float mu[kLatents];
  for (auto _ : state) {
    if (encoder.encode(scene_frame().data(), mu) != Status::kOk) {
      state.SkipWithError("encode failed");
      break;
    }
    benchmark::DoNotOptimize(mu);
  }
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(std::string("batch 1, 1 thread, ") + simd_path());
}

}  // namespace curio::nn::bench
