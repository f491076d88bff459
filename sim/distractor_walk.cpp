#include "sim/distractor_walk.hpp"

#include <algorithm>

#include "sim/scene.hpp"

namespace curio::sim {

DistractorWalk::DistractorWalk(double noise_std, uint64_t seed)
    : prng_(seed, kStream), seed_(seed), noise_std_(noise_std), position_(kDistractorStart) {}

void DistractorWalk::reset() {
  position_ = kDistractorStart;
}

void DistractorWalk::reset_to_episode(uint64_t episode) {
  prng_.reseed(seed_, kStream);  // no Gaussian spare: each episode ends on a pair boundary
  if (noise_std_ != 0.0) prng_.advance(episode * kDrawsPerEpisode);
  position_ = kDistractorStart;
}

void DistractorWalk::step() {
  if (noise_std_ == 0.0) return;
  const double dx = noise_std_ * prng_.normal();
  const double dy = noise_std_ * prng_.normal();
  position_.x = std::clamp(position_.x + dx, -kDistractorBound, kDistractorBound);
  position_.y = std::clamp(position_.y + dy, -kDistractorBound, kDistractorBound);
}

}  // namespace curio::sim
