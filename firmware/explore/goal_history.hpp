// The (goal, reached module outcome) pairs of all exploit episodes so far, tagged with their
// module: the data the interest model's progress is measured against (SPEC §2.5). One pool
// shared by all modules, because there is at most one exploit per step in total.
#pragma once
#include <cstdint>

#include "firmware/explore/config.hpp"
#include "firmware/explore/schedule.hpp"
#include "firmware/explore/status.hpp"

namespace curio {

class GoalHistory {
 public:
  static constexpr int kCapacity = kGoalHistoryCapacity;

  void reset() { size_ = 0; }

  // Records one exploit of `module`: goal and reached outcome, `n` values each.
  // kFull (counted, unchanged) when no room is left.
  Status append(int module, const float* goal, const float* reached, int n);

  // Index of module's past goal nearest to `goal` (Euclidean over `n` values, lowest index
  // wins ties), or -1 if the module has none.
  int nearest_goal(int module, const float* goal, int n) const;

  int size() const { return size_; }
  int module(int i) const { return module_[i]; }
  const float* goal(int i) const { return goal_[i]; }
  const float* reached(int i) const { return reached_[i]; }
  uint32_t rejected_full() const { return rejected_full_; }

 private:
  float goal_[kCapacity][kMaxOutcomeDim];
  float reached_[kCapacity][kMaxOutcomeDim];
  uint8_t module_[kCapacity];
  int size_ = 0;
  uint32_t rejected_full_ = 0;
};

}  // namespace curio
