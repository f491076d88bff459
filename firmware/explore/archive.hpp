// Fixed-capacity archive of episodes: how θ was made and the outcome (outcome_dim floats,
// chosen at reset) of every executed episode, in execution order.
//
// Representation (compact, exact). Every θ the Explorer proposes is one of
//   random:  random θ number r of the run (bootstrap, RPE, too-few-outcomes fallback);
//   explore: clip(θ of archived entry p + σ · explore noise number x, −1, 1);
//   exploit: θ of archived entry p, unchanged.
// So instead of 49 floats (196 bytes) an entry stores a 4-byte ThetaRecipe: (kRandom, r),
// (p, x), or for an exploit a copy of entry p's recipe (an exploit adds no depth). theta(i)
// re-makes θ from the recipe chain with ThetaGenerator — the same float operations as the
// proposal, so a regenerated θ equals the proposed one bit for bit and every result (archive
// checksums, lab summaries) is the same as with a float θ archive.
// Bounded cost: when an explore entry gets a child while kThetaPoolDepth noise vectors deep,
// that parent's θ is regenerated once into a pool of kThetaPoolCapacity float θ and its recipe
// becomes (kPooled, slot) (pooling the parent, not the child, lets one slot serve all its
// children: a step's 4 explores share one θ_nn). A regeneration then costs at most
// kThetaPoolDepth noise vectors plus one random θ or one pool copy. When the pool is full,
// deeper chains are still exact, only slower (pool_overflows() counts them). Outcomes are
// stored per dimension (one contiguous column per
// outcome dimension) so a module's nearest-neighbour scan reads only its own dimensions.
#pragma once
#include <cstdint>
#include <type_traits>

#include "firmware/explore/config.hpp"
#include "firmware/explore/status.hpp"
#include "firmware/explore/theta_generator.hpp"

namespace curio {

// Archive indices and draw numbers: 16 bit while the capacity allows it.
using ArchiveIndex = std::conditional_t<(kArchiveCapacity <= 32767), int16_t, int32_t>;
using DrawNumber = std::make_unsigned_t<ArchiveIndex>;

// How one θ was made (see above).
struct ThetaRecipe {
  static constexpr ArchiveIndex kRandom = -1;  // draw = random θ number
  static constexpr ArchiveIndex kPooled = -2;  // draw = pool slot
  ArchiveIndex parent = kRandom;               // ≥ 0: explore around entry `parent`
  DrawNumber draw = 0;                         // explore: noise number

  static ThetaRecipe random(int ordinal) { return {kRandom, static_cast<DrawNumber>(ordinal)}; }
  static ThetaRecipe explore(int parent, int noise_ordinal) {
    return {static_cast<ArchiveIndex>(parent), static_cast<DrawNumber>(noise_ordinal)};
  }
};
static_assert(sizeof(ThetaRecipe) == 2 * sizeof(ArchiveIndex), "recipe is two indices");

class Archive {
 public:
  static constexpr int kCapacity = kArchiveCapacity;
  static constexpr int kPoolCapacity = kThetaPoolCapacity;
  static constexpr int kPoolDepth = kThetaPoolDepth;

  // Empties the archive, fixes the outcome dimension (1..kMaxOutcomeDim) and the generator
  // every θ of the run comes from.
  Status reset(int outcome_dim, const ThetaGenerator& generator);

  // Appends one episode whose θ `recipe` made (and may pool its parent, see above). kFull
  // (counted, archive unchanged) when no room is left; kInvalidArgument for a null outcome,
  // before reset(), or a recipe naming a missing entry or pool slot.
  Status append(const ThetaRecipe& recipe, const float* outcome);

  // Overwrites the outcome of entry i (0 <= i < size()): a learned goal space that was
  // retrained re-encodes what the agent saw (host_tools/online). The recipe is untouched, so
  // θ(i) stays what was executed. kInvalidArgument for a bad index or a null outcome.
  Status set_outcome(int i, const float* outcome);
  int size() const { return size_; }
  int outcome_dim() const { return outcome_dim_; }
  bool full() const { return size_ == kCapacity; }

  // θ of entry i (0 <= i < size()), regenerated.
  void theta(int i, float out[kThetaDim]) const;
  ThetaRecipe recipe(int i) const { return recipe_[i]; }
  // Noise vectors theta(i) applies (0 for random and pooled entries), ≤ kPoolDepth unless
  // the pool overflowed.
  int depth(int i) const;
  // Explore generations between entry i and its random ancestor (pooling ignored).
  int lineage_depth(int i) const;

  float outcome(int i, int d) const { return outcome_[d][i]; }
  // All episodes' values of outcome dimension d, index 0..size()-1.
  const float* outcome_column(int d) const { return outcome_[d]; }
  const ThetaGenerator& generator() const { return generator_; }

  int pooled() const { return pooled_; }
  uint32_t pool_overflows() const { return pool_overflows_; }
  uint32_t rejected_full() const { return rejected_full_; }

 private:
  // The first entry up entry i's recipe chain that is random or pooled; *levels = explores.
  int chain_base(int i, int* levels) const;
  void pool(int i);  // θ of entry i into the next pool slot; i's recipe names the slot

  ThetaRecipe recipe_[kCapacity];
  float outcome_[kMaxOutcomeDim][kCapacity];
  float pool_[kPoolCapacity > 0 ? kPoolCapacity : 1][kThetaDim];
  uint16_t pool_lineage_[kPoolCapacity > 0 ? kPoolCapacity : 1];  // lineage depth of a slot
  ThetaGenerator generator_;
  int size_ = 0;
  int outcome_dim_ = 0;
  int pooled_ = 0;
  uint32_t pool_overflows_ = 0;
  uint32_t rejected_full_ = 0;
};

static_assert(kArchiveCapacity <= 65535, "pool lineage depths are 16 bit");

}  // namespace curio
