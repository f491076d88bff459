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

  // Back to the start position; the random stream continues (it spans episodes).
  void reset();

  // position += N(0, noise²) per coordinate (x drawn first), then clipped to
  // [−0.95, 0.95]². With noise 0 nothing is drawn and the position stays put.
  void step();

  const Vec2& position() const { return position_; }

 private:
  Prng prng_;
  double noise_std_;
  Vec2 position_;
};

}  // namespace curio::sim
