#include "firmware/explore/module_layouts.hpp"

namespace curio {

Status set_efr_modules(ExplorerConfig& c, Algorithm algorithm) {
  c.algorithm = algorithm;
  c.outcome_dim = kEfrOutcomeDim;
  c.goal_kind = GoalKind::kUniformBox;
  for (auto& m : c.modules) m = ModuleDims{};
  switch (algorithm) {
    case Algorithm::kRpe:
      c.n_modules = 0;
      break;
    case Algorithm::kRge:
      c.n_modules = 1;
      c.modules[0] = ModuleDims{4, {kEfrDistractorX, kEfrDistractorY, kEfrBallX, kEfrBallY}};
      break;
    case Algorithm::kMge:
      c.n_modules = 2;
      c.modules[0] = ModuleDims{2, {kEfrDistractorX, kEfrDistractorY}};
      c.modules[1] = ModuleDims{2, {kEfrBallX, kEfrBallY}};
      break;
    default:
      return Status::kInvalidArgument;
  }
  return Status::kOk;
}

Status set_latent_modules(ExplorerConfig& c, const uint8_t kl_order[kLatentDim], int group_size) {
  if (kl_order == nullptr || group_size < 1 || group_size > kLatentDim ||
      kLatentDim % group_size != 0) {
    return Status::kInvalidArgument;
  }
  bool seen[kLatentDim] = {};
  for (int i = 0; i < kLatentDim; ++i) {
    if (kl_order[i] >= kLatentDim || seen[kl_order[i]]) return Status::kInvalidArgument;
    seen[kl_order[i]] = true;
  }
  const int n_modules = kLatentDim / group_size;
  static_assert(kLatentDim <= kMaxModules, "10 single-latent modules must fit");
  c.algorithm = n_modules == 1 ? Algorithm::kRge : Algorithm::kMge;
  c.outcome_dim = kLatentDim;
  c.goal_kind = GoalKind::kClippedNormal;
  c.n_modules = n_modules;
  for (auto& m : c.modules) m = ModuleDims{};
  for (int k = 0; k < n_modules; ++k) {
    c.modules[k].n_dims = group_size;
    for (int j = 0; j < group_size; ++j) c.modules[k].dims[j] = kl_order[k * group_size + j];
  }
  return Status::kOk;
}

}  // namespace curio
