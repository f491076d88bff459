#include "firmware/explore/interest_model.hpp"

#include <cmath>

namespace curio {

void InterestModel::reset(int n_modules, float competence_cap, float window,
                          CompetenceMeasure measure) {
  n_modules_ = n_modules;
  measure_ = measure;
  cap_ = competence_cap;
  window_ = window;
  history_.reset();
  for (int k = 0; k < kMaxModules; ++k) {
    progress_[k] = kInitialProgress;
    interest_[k] = kInitialProgress;
  }
}

void InterestModel::restart(const float* progress) {
  history_.reset();
  for (int k = 0; k < n_modules_; ++k) {
    progress_[k] = progress[k];
    interest_[k] = progress[k] < 0.0f ? -progress[k] : progress[k];
  }
}

float InterestModel::competence(const float* goal, const float* reached, int n, float cap,
                                CompetenceMeasure measure) {
  float s = 0.0f;
  for (int j = 0; j < n; ++j) {
    const float e = goal[j] - reached[j];
    s = s + e * e;
  }
  const float dist = std::sqrt(s);
  if (measure == CompetenceMeasure::kScaled) return -dist / cap;
  return -(dist < cap ? dist : cap);
}

float InterestModel::update(int module, const float* goal, const float* reached, int n) {
  const float c = competence(goal, reached, n, cap_, measure_);
  const int j = history_.nearest_goal(module, goal, n);
  const float p = j < 0 ? 0.0f : c - competence(goal, history_.reached(j), n, cap_, measure_);
  progress_[module] = progress_[module] + (p - progress_[module]) / window_;
  interest_[module] = std::fabs(progress_[module]);
  history_.append(module, goal, reached, n);
  return p;
}

}  // namespace curio
