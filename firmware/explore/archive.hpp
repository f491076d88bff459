// Fixed-capacity archive of episodes: θ (kThetaDim floats) and the outcome (outcome_dim
// floats, chosen at reset) of every executed episode, in execution order. Outcomes are stored
// per dimension (one contiguous column per outcome dimension) so a module's nearest-neighbour
// scan reads only its own dimensions, sequentially.
#pragma once
#include <cstdint>

#include "firmware/explore/config.hpp"
#include "firmware/explore/status.hpp"

namespace curio {

class Archive {
 public:
  static constexpr int kCapacity = kArchiveCapacity;

  // Empties the archive and fixes the outcome dimension (1..kMaxOutcomeDim).
  Status reset(int outcome_dim);

  // Appends one episode. kFull (counted, archive unchanged) when no room is left;
  // kInvalidArgument for null pointers or before reset().
  Status append(const float theta[kThetaDim], const float* outcome);

  int size() const { return size_; }
  int outcome_dim() const { return outcome_dim_; }
  bool full() const { return size_ == kCapacity; }

  const float* theta(int i) const { return theta_[i]; }
  float outcome(int i, int d) const { return outcome_[d][i]; }
  // All episodes' values of outcome dimension d, index 0..size()-1.
  const float* outcome_column(int d) const { return outcome_[d]; }

  uint32_t rejected_full() const { return rejected_full_; }

 private:
  float theta_[kCapacity][kThetaDim];
  float outcome_[kMaxOutcomeDim][kCapacity];
  int size_ = 0;
  int outcome_dim_ = 0;
  uint32_t rejected_full_ = 0;
};

}  // namespace curio
