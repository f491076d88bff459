#include "firmware/explore/nearest_neighbour.hpp"

namespace curio {
namespace {

// Entries per block: distances of a block are computed dimension by dimension into a small
// stack buffer (vectorisable), then scanned for the minimum.
constexpr int kBlock = 256;

}  // namespace

int nearest_neighbour(const Archive& archive, const uint8_t* dims, int n_dims, const float* goal,
                      TieRule tie_rule, float* distance_sq) {
  const int n = archive.size();
  if (n == 0 || dims == nullptr || goal == nullptr || n_dims < 1 ||
      n_dims > archive.outcome_dim()) {
    return -1;
  }
  for (int j = 0; j < n_dims; ++j) {
    if (dims[j] >= archive.outcome_dim()) return -1;
  }

  float dist[kBlock];
  int best = -1;
  float best_d = 0.0f;
  for (int base = 0; base < n; base += kBlock) {
    const int len = (n - base) < kBlock ? (n - base) : kBlock;
    {
      const float* col = archive.outcome_column(dims[0]) + base;
      const float g = goal[0];
      for (int i = 0; i < len; ++i) {
        const float e = col[i] - g;
        dist[i] = e * e;
      }
    }
    for (int j = 1; j < n_dims; ++j) {
      const float* col = archive.outcome_column(dims[j]) + base;
      const float g = goal[j];
      for (int i = 0; i < len; ++i) {
        const float e = col[i] - g;
        dist[i] = dist[i] + e * e;
      }
    }
    if (tie_rule == TieRule::kEarliest) {
      for (int i = 0; i < len; ++i) {
        if (best < 0 || dist[i] < best_d) {
          best = base + i;
          best_d = dist[i];
        }
      }
    } else {
      for (int i = 0; i < len; ++i) {
        if (best < 0 || dist[i] <= best_d) {
          best = base + i;
          best_d = dist[i];
        }
      }
    }
  }
  if (distance_sq != nullptr) *distance_sq = best_d;
  return best;
}

}  // namespace curio
