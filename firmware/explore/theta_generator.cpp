#include "firmware/explore/theta_generator.hpp"

namespace curio {
namespace {

float clip_unit(float v) {
  return v > 1.0f ? 1.0f : (v < -1.0f ? -1.0f : v);
}

}  // namespace

void ThetaGenerator::reset(uint64_t seed, float sigma, const float* ladder) {
  random_start_.reseed(seed, kStreamRandomTheta);
  noise_start_.reseed(seed, kStreamNoise);
  sigma_ = sigma;
  has_ladder_ = ladder != nullptr;
  for (int i = 0; i < kLadderSteps; ++i) ladder_[i] = has_ladder_ ? ladder[i] : 1.0f;
}

void ThetaGenerator::random_theta(uint32_t ordinal, float theta[kThetaDim]) const {
  Prng rng = random_start_;
  rng.advance(static_cast<uint64_t>(ordinal) * kThetaDim * Prng::kStepsPerUniform);
  for (int i = 0; i < kThetaDim; ++i) theta[i] = static_cast<float>(rng.uniform(-1.0, 1.0));
}

void ThetaGenerator::add_noise(uint32_t ordinal, float theta[kThetaDim]) const {
  // Normal value k is half of Box–Muller pair k / 2; an odd first value is the sine of the
  // pair whose cosine ended the previous noise vector, so compute that pair and drop the cosine.
  const uint64_t first = static_cast<uint64_t>(ordinal) * kThetaDim;
  Prng rng = noise_start_;
  rng.advance(first / 2u * Prng::kStepsPerNormalPair);
  if (first % 2u != 0u) static_cast<void>(rng.normal());
  const float sigma = has_ladder_ ? sigma_ * ladder_[ordinal % static_cast<uint32_t>(kLadderSteps)] : sigma_;
  for (int i = 0; i < kThetaDim; ++i) {
    const auto n = static_cast<float>(rng.normal());
    theta[i] = clip_unit(theta[i] + sigma * n);
  }
}

}  // namespace curio
