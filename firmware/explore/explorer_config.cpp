#include "firmware/explore/explorer_config.hpp"

#include <cmath>

#include "firmware/explore/schedule.hpp"

namespace curio {
namespace {

bool finite_in(float v, float lo, float hi) {
  return std::isfinite(v) && v >= lo && v <= hi;
}

bool valid_module(const ModuleDims& m, int outcome_dim) {
  if (m.n_dims < 1 || m.n_dims > outcome_dim) return false;
  for (int j = 0; j < m.n_dims; ++j) {
    if (m.dims[j] >= outcome_dim) return false;
    for (int i = 0; i < j; ++i) {
      if (m.dims[i] == m.dims[j]) return false;
    }
  }
  return true;
}

}  // namespace

Status validate(const ExplorerConfig& c) {
  if (c.outcome_dim < 1 || c.outcome_dim > kMaxOutcomeDim) return Status::kInvalidConfig;
  if (c.n_bootstrap < 0 || c.n_episodes < 0) return Status::kInvalidConfig;
  const bool goals = c.algorithm == Algorithm::kRge || c.algorithm == Algorithm::kMge;
  if (!goals && c.algorithm != Algorithm::kRpe) return Status::kInvalidConfig;
  if (goals) {
    if (c.algorithm == Algorithm::kRge && c.n_modules != 1) return Status::kInvalidConfig;
    if (c.n_modules < 1 || c.n_modules > kMaxModules) return Status::kInvalidConfig;
    for (int k = 0; k < c.n_modules; ++k) {
      if (!valid_module(c.modules[k], c.outcome_dim)) return Status::kInvalidConfig;
    }
    if (c.goal_kind != GoalKind::kUniformBox && c.goal_kind != GoalKind::kClippedNormal) {
      return Status::kInvalidConfig;
    }
    if (!(std::isfinite(c.goal_bound) && c.goal_bound > 0.0f)) return Status::kInvalidConfig;
    if (!finite_in(c.goal_scale, 1e-3f, 1e3f)) return Status::kInvalidConfig;
    if (!finite_in(c.sigma, 0.0f, 1e3f)) return Status::kInvalidConfig;
    if (!(std::isfinite(c.competence_cap) && c.competence_cap > 0.0f)) {
      return Status::kInvalidConfig;
    }
    if (c.competence_measure != CompetenceMeasure::kClipped &&
        c.competence_measure != CompetenceMeasure::kScaled) {
      return Status::kInvalidConfig;
    }
    if (!finite_in(c.window, 1.0f, 1e9f)) return Status::kInvalidConfig;
    if (!finite_in(c.epsilon, 0.0f, 1.0f)) return Status::kInvalidConfig;
    if (c.n_episodes % kEpisodesPerStep != 0) return Status::kInvalidConfig;
    if (!finite_in(c.frontier_share, 0.0f, 1.0f)) return Status::kInvalidConfig;
    if (has_sigma_ladder(c)) {
      for (const float m : c.sigma_ladder)
        if (!finite_in(m, 1e-6f, 100.0f)) return Status::kInvalidConfig;
    }
    if (c.tie_rule != TieRule::kEarliest && c.tie_rule != TieRule::kLatest) {
      return Status::kInvalidConfig;
    }
  }
  if (static_cast<long long>(c.n_bootstrap) + c.n_episodes > kArchiveCapacity) {
    return Status::kCapacityTooSmall;
  }
  return Status::kOk;
}

bool has_sigma_ladder(const ExplorerConfig& c) {
  for (const float m : c.sigma_ladder)
    if (m != 0.0f) return true;
  return false;
}

}  // namespace curio
