// The compact archive: recipes regenerate θ exactly, exploits share their source's recipe,
// deep explore chains are cut by the θ pool, and bad recipes are refused.
#include "firmware/explore/archive.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <vector>

namespace curio {
namespace {

ThetaGenerator generator_for(uint64_t seed) {
  ThetaGenerator g;
  g.reset(seed, 0.05f);
  return g;
}

bool same_theta(const float* a, const float* b) {
  return std::memcmp(a, b, sizeof(float) * kThetaDim) == 0;
}

TEST(Archive, RegeneratesRandomExploreAndExploitThetaExactly) {
  auto a = std::make_unique<Archive>();
  const ThetaGenerator g = generator_for(9);
  ASSERT_EQ(a->reset(3, g), Status::kOk);
  float t0[kThetaDim], t1[kThetaDim], t2[kThetaDim], t3[kThetaDim];
  g.random_theta(4, t0);
  std::memcpy(t1, t0, sizeof t0);
  g.add_noise(7, t1);
  std::memcpy(t2, t1, sizeof t1);
  g.add_noise(8, t2);
  const float o[3] = {1.0f, -2.0f, 0.5f};
  ASSERT_EQ(a->append(ThetaRecipe::random(4), o), Status::kOk);
  ASSERT_EQ(a->append(ThetaRecipe::explore(0, 7), o), Status::kOk);
  ASSERT_EQ(a->append(ThetaRecipe::explore(1, 8), o), Status::kOk);
  ASSERT_EQ(a->append(a->recipe(2), o), Status::kOk);  // an exploit of entry 2
  EXPECT_EQ(a->size(), 4);
  EXPECT_EQ(a->outcome_dim(), 3);
  const float* want[4] = {t0, t1, t2, t2};
  const int depth[4] = {0, 1, 2, 2};
  for (int i = 0; i < 4; ++i) {
    a->theta(i, t3);
    EXPECT_TRUE(same_theta(t3, want[i])) << "entry " << i;
    EXPECT_EQ(a->depth(i), depth[i]);
    EXPECT_EQ(a->lineage_depth(i), depth[i]);
  }
  EXPECT_FALSE(same_theta(t0, t1));
  EXPECT_EQ(a->outcome(3, 1), -2.0f);
  EXPECT_EQ(a->outcome_column(2)[1], 0.5f);
  EXPECT_EQ(a->pooled(), 0);
}

TEST(Archive, PoolCutsDeepChainsAndStaysExact) {
  auto a = std::make_unique<Archive>();
  const ThetaGenerator g = generator_for(3);
  ASSERT_EQ(a->reset(1, g), Status::kOk);
  // One chain, each entry exploring around the previous one.
  const int n = 3 * Archive::kPoolDepth + 2;
  std::vector<float> thetas(static_cast<size_t>(n) * kThetaDim);
  float* t = thetas.data();
  g.random_theta(0, t);
  const float o[1] = {0.0f};
  ASSERT_EQ(a->append(ThetaRecipe::random(0), o), Status::kOk);
  for (int i = 1; i < n; ++i) {
    float* ti = t + i * kThetaDim;
    std::memcpy(ti, ti - kThetaDim, sizeof(float) * kThetaDim);
    g.add_noise(static_cast<uint32_t>(i - 1), ti);
    ASSERT_EQ(a->append(ThetaRecipe::explore(i - 1, i - 1), o), Status::kOk);
  }
  float out[kThetaDim];
  for (int i = 0; i < n; ++i) {
    a->theta(i, out);
    EXPECT_TRUE(same_theta(out, t + i * kThetaDim)) << "entry " << i;
    EXPECT_LE(a->depth(i), Archive::kPoolDepth);
    EXPECT_EQ(a->lineage_depth(i), i);
  }
  EXPECT_EQ(a->pooled(), 3);  // entries K, 2K, 3K, pooled when they got a child
  for (int m = 1; m <= 3; ++m) {
    EXPECT_EQ(a->recipe(m * Archive::kPoolDepth).parent, ThetaRecipe::kPooled);
  }
  EXPECT_EQ(a->pool_overflows(), 0u);
}

TEST(Archive, RejectsBadDimensionsNullsAndUnknownSources) {
  auto a = std::make_unique<Archive>();
  const ThetaGenerator g = generator_for(1);
  EXPECT_EQ(a->reset(0, g), Status::kInvalidArgument);
  EXPECT_EQ(a->reset(kMaxOutcomeDim + 1, g), Status::kInvalidArgument);
  const float outcome[1] = {0.0f};
  EXPECT_EQ(a->append(ThetaRecipe{}, outcome), Status::kInvalidArgument);  // no reset
  ASSERT_EQ(a->reset(1, g), Status::kOk);
  EXPECT_EQ(a->append(ThetaRecipe{}, nullptr), Status::kInvalidArgument);
  EXPECT_EQ(a->append(ThetaRecipe::explore(0, 0), outcome), Status::kInvalidArgument);
  EXPECT_EQ(a->append({ThetaRecipe::kPooled, 0}, outcome), Status::kInvalidArgument);
  EXPECT_EQ(a->append({-3, 0}, outcome), Status::kInvalidArgument);
  EXPECT_EQ(a->size(), 0);
}

TEST(Archive, ReportsFullAndCountsRejections) {
  auto a = std::make_unique<Archive>();
  ASSERT_EQ(a->reset(1, generator_for(2)), Status::kOk);
  const float outcome[1] = {1.0f};
  for (int i = 0; i < Archive::kCapacity; ++i) {
    ASSERT_EQ(a->append(ThetaRecipe::random(i), outcome), Status::kOk);
  }
  EXPECT_TRUE(a->full());
  EXPECT_EQ(a->append(ThetaRecipe{}, outcome), Status::kFull);
  EXPECT_EQ(a->append(ThetaRecipe{}, outcome), Status::kFull);
  EXPECT_EQ(a->size(), Archive::kCapacity);
  EXPECT_EQ(a->rejected_full(), 2u);
}

}  // namespace
}  // namespace curio
