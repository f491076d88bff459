#include "firmware/explore/sparse_goal.hpp"

namespace curio {

float nearest_other_distance_sq(const Archive& archive, const GoalModule& module, int i) {
  const int n = archive.size();
  if (i < 0 || i >= n || n < 2) return -1.0f;
  float at[kMaxOutcomeDim];
  for (int j = 0; j < module.n_dims; ++j) at[j] = archive.outcome(i, module.dims[j]);
  float best = -1.0f;
  for (int e = 0; e < n; ++e) {
    if (e == i) continue;
    float d = 0.0f;
    for (int j = 0; j < module.n_dims; ++j) {
      const float x = archive.outcome(e, module.dims[j]) - at[j];
      d = d + x * x;
    }
    if (best < 0.0f || d < best) best = d;
  }
  return best;
}

int sparse_archive_goal(const Archive& archive, const GoalModule& module, int candidates,
                        Prng& prng, float* goal) {
  const int n = archive.size();
  if (n < 1 || candidates < 1 || goal == nullptr) return -1;
  int chosen = -1;
  float chosen_d = -1.0f;
  for (int c = 0; c < candidates; ++c) {
    const int i = static_cast<int>(prng.below(static_cast<uint32_t>(n)));
    const float d = nearest_other_distance_sq(archive, module, i);
    if (chosen < 0 || d > chosen_d) {
      chosen = i;
      chosen_d = d;
    }
  }
  for (int j = 0; j < module.n_dims; ++j) goal[j] = archive.outcome(chosen, module.dims[j]);
  return chosen;
}

}  // namespace curio
