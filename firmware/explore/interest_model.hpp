// Interest of each goal module = |smoothed learning progress| (SPEC §2.5, exactly):
//   after module k's exploit episode with goal g and reached module outcome r,
//     c     = competence(g, r)
//     j     = module k's past goal nearest to g        (none yet: p = 0)
//     c_old = competence(g, r_j)   (r_j scored against the CURRENT goal g)
//     p     = c − c_old
//     cp   += (p − cp) / W
//     interest_k = |cp|
//   cp and interest start at 1e-5. D and W (window) are configurable, and so is the measure:
//     kClipped: competence = −min(‖g − r‖, D)   (SPEC §2.5 as written)
//     kScaled:  competence = −‖g − r‖ / D       (explauto's competence_dist as the reference
//               code ran it: `min(-dist_min, -norm(target - reached)) / dist_max`, with
//               dist_max = D; D only rescales every progress, so it barely moves the choice)
// Then (g, r) joins module k's goal history.
#pragma once
#include <cstdint>

#include "firmware/explore/config.hpp"
#include "firmware/explore/goal_history.hpp"
#include "firmware/explore/status.hpp"

namespace curio {

enum class CompetenceMeasure : uint8_t { kClipped, kScaled };

constexpr const char* to_string(CompetenceMeasure m) {
  return m == CompetenceMeasure::kClipped ? "clip" : "scale";
}

class InterestModel {
 public:
  static constexpr float kInitialProgress = 1e-5f;

  // D > 0, W ≥ 1, 1 ≤ n_modules ≤ kMaxModules (checked by the caller's config validation).
  void reset(int n_modules, float competence_cap, float window,
             CompetenceMeasure measure = CompetenceMeasure::kClipped);

  // A restart for replacement goal modules (a retrained goal space): the goal history is emptied
  // (its goals lie in the old space) and module k's cp becomes progress[k] (interest |cp|),
  // n_modules unchanged. The caller carries cp over from the old modules (host_tools/online).
  void restart(const float* progress);
  // c = −min(‖g − r‖, cap) (kClipped) or −‖g − r‖ / cap (kScaled) over n values.
  static float competence(const float* goal, const float* reached, int n, float cap,
                          CompetenceMeasure measure = CompetenceMeasure::kClipped);

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
  CompetenceMeasure measure_ = CompetenceMeasure::kClipped;
};

}  // namespace curio
