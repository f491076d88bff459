// How every θ of a run is made, at a stream position instead of "the next draws": random θ
// number r is uniform draws 49r .. 49r + 48 of the random-θ stream, explore noise number x is
// normal draws 49x .. 49x + 48 of the noise stream (PCG32 jump-ahead, Prng::advance). The
// Explorer makes θ through here and the Archive re-makes archived θ through here, so a
// regenerated θ is the same float operations as the proposed one, bit for bit.
#pragma once
#include <cstdint>

#include "firmware/explore/config.hpp"
#include "firmware/explore/prng.hpp"
#include "firmware/explore/schedule.hpp"

namespace curio {

class ThetaGenerator {
 public:
  // Stream ids of Prng(seed, stream) (the Explorer's other two streams are 1 and 2).
  static constexpr uint64_t kStreamRandomTheta = 3;
  static constexpr uint64_t kStreamNoise = 4;
  // σ ladder values: one per explore episode of a step.
  static constexpr int kLadderSteps = kExploreEpisodesPerStep;

  // The run's seed and the explore noise std σ.
  // ladder (optional, kLadderSteps values): explore noise number x has std σ·ladder[x mod 4]
  // instead of σ (a step's 4 explore episodes take consecutive numbers: small and large steps
  // alike). nullptr: σ for every number (SPEC §2.2).
  void reset(uint64_t seed, float sigma, const float* ladder = nullptr);

  // θ = random θ number `ordinal`: θ_i ~ U(−1, 1), 49 uniform draws.
  void random_theta(uint32_t ordinal, float theta[kThetaDim]) const;

  // θ ← clip(θ + σ·n, −1, 1), n = explore noise number `ordinal` (49 normal draws).
  void add_noise(uint32_t ordinal, float theta[kThetaDim]) const;

  float sigma() const { return sigma_; }

 private:
  Prng random_start_;  // both streams as seeded: every position is a jump from here
  Prng noise_start_;
  float sigma_ = 0.0f;
  float ladder_[kLadderSteps] = {};
  bool has_ladder_ = false;
};

}  // namespace curio
