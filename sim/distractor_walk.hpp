// The distractor's random walk (SPEC §1.1 step 4), one component shared by both
// physics so that the same seed gives the same distractor trajectory in each.
#pragma once
#include <cstdint>

#include "firmware/explore/prng.hpp"
#include "sim/world.hpp"

namespace curio::sim {

class DistractorWalk {
 public:
  // PCG stream of the walk: keeps it independent of other generators that a caller
  // seeds with the same number (e.g. the explorer's θ sampling).
  static constexpr uint64_t kStream = 0x64697374726163ULL;  // "distrac"

  DistractorWalk(double noise_std, uint64_t seed);

  // next_u32() draws of one step, and of one episode of kStepsPerEpisode steps (noise > 0):
  // every step draws exactly one Box–Muller pair, so episodes start on a pair boundary.
  static constexpr uint64_t kDrawsPerStep = Prng::kStepsPerNormalPair;
  static constexpr uint64_t kDrawsPerEpisode = kDrawsPerStep * kStepsPerEpisode;

  // Back to the start position; the random stream continues (it spans episodes).
  void reset();

  // Back to the start position with the stream where `episode` episodes of kStepsPerEpisode
  // steps each, from the seed, leave it: the walk of episode `episode` whatever ran before
  // (a replayed episode, or the first one after a restart, is the same as in an unbroken run).
  // O(log episode) (PCG jump-ahead).
  void reset_to_episode(uint64_t episode);

  // position += N(0, noise²) per coordinate (x drawn first), then clipped to
  // [−0.95, 0.95]². With noise 0 nothing is drawn and the position stays put.
  void step();

  const Vec2& position() const { return position_; }

 private:
  Prng prng_;
  uint64_t seed_;
  double noise_std_;
  Vec2 position_;
};

}  // namespace curio::sim
