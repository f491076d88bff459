#include "firmware/explore/archive.hpp"

namespace curio {

Status Archive::reset(int outcome_dim) {
  if (outcome_dim < 1 || outcome_dim > kMaxOutcomeDim) return Status::kInvalidArgument;
  outcome_dim_ = outcome_dim;
  size_ = 0;
  rejected_full_ = 0;
  return Status::kOk;
}

Status Archive::append(const float theta[kThetaDim], const float* outcome) {
  if (theta == nullptr || outcome == nullptr || outcome_dim_ == 0) return Status::kInvalidArgument;
  if (size_ == kCapacity) {
    ++rejected_full_;
    return Status::kFull;
  }
  for (int k = 0; k < kThetaDim; ++k) theta_[size_][k] = theta[k];
  for (int d = 0; d < outcome_dim_; ++d) outcome_[d][size_] = outcome[d];
  ++size_;
  return Status::kOk;
}

}  // namespace curio
