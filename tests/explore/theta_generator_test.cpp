// θ made at a stream position equals θ made from the streams drawn in order: PCG32 jump-ahead,
// random θ number r, explore noise number x (including the Box–Muller spare of odd starts).
#include "firmware/explore/theta_generator.hpp"

#include <gtest/gtest.h>

#include <cstring>

namespace curio {
namespace {

float clip_unit(float v) {
  return v > 1.0f ? 1.0f : (v < -1.0f ? -1.0f : v);
}

TEST(Prng, AdvanceEqualsThatManySteps) {
  for (const uint64_t n : {0ull, 1ull, 2ull, 97ull, 1000ull, 123457ull}) {
    Prng stepped(42, 4), jumped(42, 4);
    for (uint64_t i = 0; i < n; ++i) stepped.next_u32();
    jumped.advance(n);
    for (int i = 0; i < 8; ++i) ASSERT_EQ(stepped.next_u32(), jumped.next_u32()) << "n = " << n;
  }
}

TEST(ThetaGenerator, RandomThetaNumberRIsTheRthBlockOfUniformDraws) {
  ThetaGenerator g;
  g.reset(17, 0.05f);
  Prng in_order(17, ThetaGenerator::kStreamRandomTheta);
  float want[kThetaDim], got[kThetaDim];
  for (uint32_t r = 0; r < 40; ++r) {
    for (float& v : want) v = static_cast<float>(in_order.uniform(-1.0, 1.0));
    g.random_theta(r, got);
    ASSERT_EQ(std::memcmp(want, got, sizeof want), 0) << "r = " << r;
  }
}

TEST(ThetaGenerator, NoiseNumberXIsTheXthBlockOfNormalDraws) {
  const float sigma = 0.3f;  // large, so that clipping happens too
  ThetaGenerator g;
  g.reset(17, sigma);
  Prng in_order(17, ThetaGenerator::kStreamNoise);
  float base[kThetaDim];
  for (int i = 0; i < kThetaDim; ++i) base[i] = -1.0f + 2.0f * static_cast<float>(i) / kThetaDim;
  float want[kThetaDim], got[kThetaDim];
  for (uint32_t x = 0; x < 40; ++x) {  // odd x start on a Box–Muller spare
    for (int i = 0; i < kThetaDim; ++i) {
      const auto n = static_cast<float>(in_order.normal());
      want[i] = clip_unit(base[i] + sigma * n);
    }
    std::memcpy(got, base, sizeof base);
    g.add_noise(x, got);
    ASSERT_EQ(std::memcmp(want, got, sizeof want), 0) << "x = " << x;
  }
}

}  // namespace
}  // namespace curio
