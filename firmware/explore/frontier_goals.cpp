#include "firmware/explore/frontier_goals.hpp"

namespace curio {

void FrontierGoals::reset(const GoalModule* modules, int n_modules) {
  for (int k = 0; k < kMaxModules; ++k) {
    for (int c = 0; c < kCells; ++c) reached_[k][c] = misses_[k][c] = 0;
    aimed_[k] = -1;
    has_grid_[k] = k < n_modules && modules[k].n_dims >= 1 && modules[k].n_dims <= 2;
    if (!has_grid_[k]) continue;
    const GoalModule& m = modules[k];
    const float half =
        m.goal_kind == GoalKind::kUniformBox ? 1.0f : m.goal_bound * m.goal_scale;
    dims_[k] = m.n_dims;
    lo_[k] = -half;
    width_[k] = 2.0f * half / static_cast<float>(kFrontierCells);
  }
}

int FrontierGoals::cell_of(int k, const float* p) const {
  int c[2] = {0, 0};
  for (int j = 0; j < dims_[k]; ++j) {
    const float x = (p[j] - lo_[k]) / width_[k];
    c[j] = x <= 0.0f ? 0 : (x >= kFrontierCells - 1 ? kFrontierCells - 1 : static_cast<int>(x));
  }
  return c[1] * kFrontierCells + c[0];
}

bool FrontierGoals::reached(int k, int cx, int cy) const {
  if (cx < 0 || cy < 0 || cx >= kFrontierCells || cy >= kFrontierCells) return false;
  if (dims_[k] == 1 && cy != 0) return false;
  return reached_[k][cy * kFrontierCells + cx] != 0;
}

void FrontierGoals::observe(int k, const float* projected) {
  if (has_grid_[k]) reached_[k][cell_of(k, projected)] = 1;
}

int FrontierGoals::reached_cells(int k) const {
  int n = 0;
  for (int c = 0; c < kCells; ++c) n += reached_[k][c];
  return n;
}

double FrontierGoals::weight(int k, int cx, int cy) const {
  const int c = cy * kFrontierCells + cx;
  if (reached_[k][c]) return 0.0;
  bool edge = false;
  for (int dy = -1; dy <= 1 && !edge; ++dy)
    for (int dx = -1; dx <= 1 && !edge; ++dx) edge = reached(k, cx + dx, cy + dy);
  if (!edge) return 0.0;
  const double m = 1.0 + misses_[k][c];
  return 1.0 / (m * m);
}

bool FrontierGoals::sample(int k, Prng& prng, float* goal) {
  aimed_[k] = -1;
  if (!has_grid_[k]) return false;
  const int rows = dims_[k] == 1 ? 1 : kFrontierCells;
  double total = 0.0;
  for (int cy = 0; cy < rows; ++cy)
    for (int cx = 0; cx < kFrontierCells; ++cx) total += weight(k, cx, cy);
  if (total <= 0.0) return false;
  // The cell the draw lands in, by the same running sum.
  const double target = prng.uniform01() * total;
  double sum = 0.0;
  for (int cy = 0; cy < rows; ++cy) {
    for (int cx = 0; cx < kFrontierCells; ++cx) {
      const double w = weight(k, cx, cy);
      sum += w;
      if (w <= 0.0 || sum <= target) continue;
      aimed_[k] = cy * kFrontierCells + cx;
      const int cell[2] = {cx, cy};
      for (int j = 0; j < dims_[k]; ++j)
        goal[j] = lo_[k] + width_[k] * (static_cast<float>(cell[j]) +
                                        static_cast<float>(prng.uniform01()));
      return true;
    }
  }
  return false;  // rounding left the draw past the last cell: no goal this time
}

void FrontierGoals::step_done(int k) {
  const int c = aimed_[k];
  if (c < 0) return;
  if (!reached_[k][c] && misses_[k][c] < 255) ++misses_[k][c];
  aimed_[k] = -1;
}

}  // namespace curio
