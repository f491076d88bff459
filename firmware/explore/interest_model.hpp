// Interest of each goal module = |smoothed learning progress| (SPEC §2.5, exactly):
//   after module k's exploit episode with goal g and reached module outcome r,
//     c     = −min(‖g − r‖, D)
//     j     = module k's past goal nearest to g        (none yet: p = 0)
//     c_old = −min(‖g − r_j‖, D)   (r_j scored against the CURRENT goal g)
//     p     = c − c_old
//     cp   += (p − cp) / W
//     interest_k = |cp|
//   cp and interest start at 1e-5. D (competence cap) and W (window) are configurable.
// Then (g, r) joins module k's goal history.
#pragma once
#include "explore/config.hpp"
#include "explore/goal_history.hpp"
#include "explore/status.hpp"

namespace curio {

class InterestModel {
 public:
  static constexpr float kInitialProgress = 1e-5f;

  // D > 0, W ≥ 1, 1 ≤ n_modules ≤ kMaxModules (checked by the caller's config validation).
  void reset(int n_modules, float competence_cap, float window);

  // c = −min(‖g − r‖, cap) over n values.
  static float competence(const float* goal, const float* reached, int n, float cap);

  // The update above for module k; returns p. kFull from the history is counted there and
  // does not stop the interest update.
  float update(int module, const float* goal, const float* reached, int n);

  int n_modules() const { return n_modules_; }
  float interest(int module) const { return interest_[module]; }
  float progress(int module) const { return progress_[module]; }  // cp
  const GoalHistory& history() const { return history_; }

 private:
  GoalHistory history_;
  float progress_[kMaxModules] = {};
  float interest_[kMaxModules] = {};
  int n_modules_ = 0;
  float cap_ = 2.0f;
  float window_ = 1000.0f;
};

}  // namespace curio
