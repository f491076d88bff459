// Tracks, in O(1) per appended episode, whether the archive holds at least two different
// outcomes for one module (SPEC §2.2: until then the module's NN query returns a random θ).
// "Different" is exact float inequality of the projected outcome (so -0 == +0).
#pragma once
#include "firmware/explore/config.hpp"

namespace curio {

class DistinctOutcomes {
 public:
  void reset() { count_ = 0; }

  // Records one projected outcome of `n` values.
  void observe(const float* projected, int n) {
    if (count_ >= 2) return;
    if (count_ == 0) {
      for (int j = 0; j < n; ++j) first_[j] = projected[j];
      count_ = 1;
      return;
    }
    for (int j = 0; j < n; ++j) {
      if (projected[j] != first_[j]) {
        count_ = 2;
        return;
      }
    }
  }

  bool has_two() const { return count_ >= 2; }

 private:
  float first_[kMaxOutcomeDim] = {};
  int count_ = 0;  // distinct values seen, saturating at 2
};

}  // namespace curio
