// A deterministic stand-in for the arm (no sim/ dependency): outcome = f(θ) with the
// structure of the engineered features [distractor x, y, ball x, y]. The "ball" stays at
// (0.6, 0.6) unless θ[0] + θ[1] > 1.2 (a rare "grasp", ~8 % of uniform θ), then it follows
// θ[2..3]; the "distractor" moves with θ[4..5] through a nonlinear map.
#pragma once
#include <cmath>

#include "firmware/explore/config.hpp"

namespace curio::test {

inline void toy_outcome(const float* theta, float* outcome) {
  outcome[0] = 0.9f * std::sin(3.0f * theta[4]);
  outcome[1] = 0.9f * std::cos(2.0f * theta[5]);
  if (theta[0] + theta[1] > 1.2f) {
    outcome[2] = 0.95f * theta[2];
    outcome[3] = 0.95f * theta[3];
  } else {
    outcome[2] = 0.6f;
    outcome[3] = 0.6f;
  }
}

// 10-D "latent" outcome for learned-goal-space configs: the 4 features, then 6 small
// deterministic nuisances.
inline void toy_latent_outcome(const float* theta, float* outcome) {
  toy_outcome(theta, outcome);
  for (int j = 4; j < 10; ++j) outcome[j] = 0.01f * theta[10 + j];
}

}  // namespace curio::test
