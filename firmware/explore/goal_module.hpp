// A goal module (SPEC §2.1–2.3): a projection of the outcome onto some of its dimensions,
// and the distribution its goals are sampled from.
#pragma once
#include <cstdint>

#include "firmware/explore/config.hpp"
#include "firmware/explore/prng.hpp"

namespace curio {

enum class GoalKind : uint8_t {
  kUniformBox,     // engineered features: g ~ U[-1, 1]^d
  kClippedNormal,  // learned latents (VAE prior): g = scale · clip(N(0, I_d), -bound, bound)
};

struct GoalModule {
  int n_dims = 0;                     // d, 1..kMaxOutcomeDim
  uint8_t dims[kMaxOutcomeDim] = {};  // outcome dimension of each module coordinate
  GoalKind goal_kind = GoalKind::kUniformBox;
  float goal_bound = 2.5f;  // only for kClippedNormal
  float goal_scale = 1.0f;  // only for kClippedNormal: 1 is SPEC §2.3's prior

  // out[j] = outcome[dims[j]], j < n_dims.
  void project(const float* outcome, float* out) const {
    for (int j = 0; j < n_dims; ++j) out[j] = outcome[dims[j]];
  }

  // Draws one goal (n_dims values) from `prng`: n_dims uniform01 draws (kUniformBox) or
  // n_dims normal draws (kClippedNormal), in coordinate order.
  void sample_goal(Prng& prng, float* goal) const;
};

}  // namespace curio
