#include "firmware/explore/archive.hpp"

namespace curio {
namespace {

// Noise numbers gathered per pass while regenerating a chain deeper than this (pool overflow).
constexpr int kChainChunk = 32;

}  // namespace

Status Archive::reset(int outcome_dim, const ThetaGenerator& generator) {
  if (outcome_dim < 1 || outcome_dim > kMaxOutcomeDim) return Status::kInvalidArgument;
  outcome_dim_ = outcome_dim;
  generator_ = generator;
  size_ = 0;
  pooled_ = 0;
  pool_overflows_ = 0;
  rejected_full_ = 0;
  return Status::kOk;
}

Status Archive::set_outcome(int i, const float* outcome) {
  if (outcome == nullptr || i < 0 || i >= size_) return Status::kInvalidArgument;
  for (int d = 0; d < outcome_dim_; ++d) outcome_[d][i] = outcome[d];
  return Status::kOk;
}

Status Archive::append(const ThetaRecipe& recipe, const float* outcome) {
  if (outcome == nullptr || outcome_dim_ == 0) return Status::kInvalidArgument;
  const bool named_ok = recipe.parent >= 0 ? recipe.parent < size_
                        : recipe.parent == ThetaRecipe::kPooled
                            ? static_cast<int>(recipe.draw) < pooled_
                            : recipe.parent == ThetaRecipe::kRandom;
  if (!named_ok) return Status::kInvalidArgument;
  if (size_ == kCapacity) {
    ++rejected_full_;
    return Status::kFull;
  }
  if (recipe.parent >= 0 && depth(recipe.parent) >= kPoolDepth) {
    if (pooled_ < kPoolCapacity) {
      pool(recipe.parent);
    } else {
      ++pool_overflows_;
    }
  }
  recipe_[size_] = recipe;
  for (int d = 0; d < outcome_dim_; ++d) outcome_[d][size_] = outcome[d];
  ++size_;
  return Status::kOk;
}

void Archive::pool(int i) {
  theta(i, pool_[pooled_]);
  pool_lineage_[pooled_] = static_cast<uint16_t>(lineage_depth(i));
  recipe_[i] = {ThetaRecipe::kPooled, static_cast<DrawNumber>(pooled_)};
  ++pooled_;
}

int Archive::chain_base(int i, int* levels) const {
  int n = 0;
  while (recipe_[i].parent >= 0) {
    i = recipe_[i].parent;
    ++n;
  }
  *levels = n;
  return i;
}

int Archive::depth(int i) const {
  int levels = 0;
  chain_base(i, &levels);
  return levels;
}

int Archive::lineage_depth(int i) const {
  int levels = 0;
  const ThetaRecipe& base = recipe_[chain_base(i, &levels)];
  return base.parent == ThetaRecipe::kPooled ? levels + pool_lineage_[base.draw] : levels;
}

void Archive::theta(int i, float out[kThetaDim]) const {
  int levels = 0;
  const ThetaRecipe& base = recipe_[chain_base(i, &levels)];
  if (base.parent == ThetaRecipe::kPooled) {
    for (int k = 0; k < kThetaDim; ++k) out[k] = pool_[base.draw][k];
  } else {
    generator_.random_theta(base.draw, out);
  }
  // Noise from the base down to entry i: generation g (1 = the base's child) is the ancestor
  // levels − g steps above i. Gathered kChainChunk at a time, oldest first.
  DrawNumber noise[kChainChunk];
  for (int first = 1; first <= levels; first += kChainChunk) {
    const int n = levels - first + 1 < kChainChunk ? levels - first + 1 : kChainChunk;
    int e = i;
    for (int up = 0; up < levels - (first + n - 1); ++up) e = recipe_[e].parent;
    for (int g = n - 1; g >= 0; --g) {
      noise[g] = recipe_[e].draw;
      e = recipe_[e].parent;
    }
    for (int g = 0; g < n; ++g) generator_.add_noise(noise[g], out);
  }
}

}  // namespace curio
