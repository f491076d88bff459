#include "firmware/explore/goal_module.hpp"

namespace curio {

void GoalModule::sample_goal(Prng& prng, float* goal) const {
  for (int j = 0; j < n_dims; ++j) {
    if (goal_kind == GoalKind::kUniformBox) {
      goal[j] = static_cast<float>(prng.uniform(-1.0, 1.0));
    } else {
      const auto g = static_cast<float>(prng.normal());
      goal[j] = goal_scale * (g > goal_bound ? goal_bound : (g < -goal_bound ? -goal_bound : g));
    }
  }
}

}  // namespace curio
