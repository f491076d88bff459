#include "firmware/explore/goal_history.hpp"

namespace curio {

Status GoalHistory::append(int module, const float* goal, const float* reached, int n) {
  if (module < 0 || module >= kMaxModules || n < 1 || n > kMaxOutcomeDim || goal == nullptr ||
      reached == nullptr) {
    return Status::kInvalidArgument;
  }
  if (size_ == kCapacity) {
    ++rejected_full_;
    return Status::kFull;
  }
  for (int j = 0; j < n; ++j) {
    goal_[size_][j] = goal[j];
    reached_[size_][j] = reached[j];
  }
  module_[size_] = static_cast<uint8_t>(module);
  ++size_;
  return Status::kOk;
}

int GoalHistory::nearest_goal(int module, const float* goal, int n) const {
  int best = -1;
  float best_d = 0.0f;
  for (int i = 0; i < size_; ++i) {
    if (module_[i] != module) continue;
    float d = 0.0f;
    for (int j = 0; j < n; ++j) {
      const float e = goal_[i][j] - goal[j];
      d = d + e * e;
    }
    if (best < 0 || d < best_d) {
      best = i;
      best_d = d;
    }
  }
  return best;
}

}  // namespace curio
