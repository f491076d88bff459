// Toy data and options for the online-training tests: a capacity schedule that opens the
// second latent group within a few dozen iterations, and scenes whose distractor walks a
// diagonal while the ball rests (or, with ball_moves, every other scene moves it).
#pragma once
#include <cstdint>
#include <vector>

#include <torch/torch.h>

#include "host_tools/online/goal_space.hpp"
#include "host_tools/online/online_options.hpp"

namespace curio::online::toy {

// Progressive latents at 3 nats each, C 0 → 12 over 60 iterations, batch 8, no anchoring.
inline OnlineOptions toy_progressive_options(uint64_t seed) {
  OnlineOptions o;
  o.seed = seed;
  o.nats_per_latent = 3.0;
  o.anchor_weight = 0.0;
  o.capacity_max = 12.0;
  o.capacity_iters = 60;
  o.batch = 8;
  return o;
}

inline torch::Tensor toy_images(int n, bool ball_moves = false) {
  std::vector<Scene> scenes;
  for (int i = 0; i < n; ++i) {
    const float t = static_cast<float>(i) / static_cast<float>(n);
    const bool moved = ball_moves && i % 2 == 1;
    const float b = moved ? -0.6f + 1.2f * static_cast<float>((i * 7) % n) / static_cast<float>(n) : 0.6f;
    scenes.push_back({b, moved ? -b : 0.6f, -0.8f + 1.6f * t, 0.7f - 1.4f * t});
  }
  return render_images(scenes, 1);
}

}  // namespace curio::online::toy
