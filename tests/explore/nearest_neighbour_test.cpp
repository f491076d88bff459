#include "firmware/explore/nearest_neighbour.hpp"

#include <gtest/gtest.h>

#include <memory>

#include "firmware/explore/prng.hpp"

namespace curio {
namespace {

std::unique_ptr<Archive> archive_of(const float (*outcomes)[2], int n) {
  auto a = std::make_unique<Archive>();
  a->reset(2, ThetaGenerator{});
  for (int i = 0; i < n; ++i) {
    a->append(ThetaRecipe{}, outcomes[i]);
  }
  return a;
}

TEST(NearestNeighbour, EmptyArchiveOrBadDimsGiveMinusOne) {
  auto a = std::make_unique<Archive>();
  a->reset(2, ThetaGenerator{});
  const uint8_t dims[2] = {0, 1};
  const float goal[2] = {0, 0};
  EXPECT_EQ(nearest_neighbour(*a, dims, 2, goal), -1);
  const float o[1][2] = {{1, 1}};
  a = archive_of(o, 1);
  const uint8_t bad[1] = {2};
  EXPECT_EQ(nearest_neighbour(*a, bad, 1, goal), -1);
  EXPECT_EQ(nearest_neighbour(*a, dims, 3, goal), -1);
  EXPECT_EQ(nearest_neighbour(*a, dims, 2, goal), 0);
}

TEST(NearestNeighbour, TiesGoToLatestByDefaultAndEarliestOnRequest) {
  // Episodes 1, 2 and 4 all left the "ball" at (0.6, 0.6), the goal's nearest point.
  const float o[5][2] = {{-1, -1}, {0.6f, 0.6f}, {0.6f, 0.6f}, {0.9f, -0.9f}, {0.6f, 0.6f}};
  auto a = archive_of(o, 5);
  const uint8_t dims[2] = {0, 1};
  const float goal[2] = {0.5f, 0.5f};
  EXPECT_EQ(nearest_neighbour(*a, dims, 2, goal), 4);
  EXPECT_EQ(nearest_neighbour(*a, dims, 2, goal, TieRule::kEarliest), 1);
  EXPECT_EQ(nearest_neighbour(*a, dims, 2, goal, TieRule::kLatest), 4);
}

TEST(NearestNeighbour, TiesAcrossScanBlocksKeepTheRule) {
  // 1,000 identical outcomes span several internal blocks.
  auto a = std::make_unique<Archive>();
  a->reset(1, ThetaGenerator{});
  const float far[1] = {5.0f};
  const float same[1] = {0.25f};
  a->append(ThetaRecipe{}, far);
  for (int i = 0; i < 1000; ++i) a->append(ThetaRecipe{}, same);
  const uint8_t dims[1] = {0};
  const float goal[1] = {0.0f};
  EXPECT_EQ(nearest_neighbour(*a, dims, 1, goal, TieRule::kEarliest), 1);
  EXPECT_EQ(nearest_neighbour(*a, dims, 1, goal, TieRule::kLatest), 1000);
}

TEST(NearestNeighbour, UsesOnlyTheModuleDimensions) {
  auto a = std::make_unique<Archive>();
  a->reset(3, ThetaGenerator{});
  const float o0[3] = {0.0f, 100.0f, 0.0f};  // nearest in dims {0, 2}
  const float o1[3] = {1.0f, 0.0f, 1.0f};    // nearest in all dims
  a->append(ThetaRecipe{}, o0);
  a->append(ThetaRecipe{}, o1);
  const float goal[2] = {0.0f, 0.0f};
  const uint8_t module[2] = {0, 2};
  EXPECT_EQ(nearest_neighbour(*a, module, 2, goal), 0);
  const float goal3[3] = {0, 0, 0};
  const uint8_t all[3] = {0, 1, 2};
  EXPECT_EQ(nearest_neighbour(*a, all, 3, goal3), 1);
}

TEST(NearestNeighbour, MatchesBruteForceOnRandomData) {
  constexpr int kEntries = 3000;
  constexpr int kDim = 6;
  auto a = std::make_unique<Archive>();
  a->reset(kDim, ThetaGenerator{});
  Prng rng(42, 9);
  float outcome[kDim];
  for (int i = 0; i < kEntries; ++i) {
    // Coarse values make exact ties common, so the tie rule is exercised too.
    for (float& v : outcome) v = static_cast<float>(rng.below(9)) * 0.25f - 1.0f;
    a->append(ThetaRecipe{}, outcome);
  }
  const uint8_t dims[3] = {4, 1, 3};
  for (int q = 0; q < 500; ++q) {
    float goal[3];
    for (float& g : goal) g = static_cast<float>(rng.uniform(-1.2, 1.2));
    int best_first = -1, best_last = -1;
    double best_d = 1e30;
    for (int i = 0; i < kEntries; ++i) {
      double d = 0.0;
      for (int j = 0; j < 3; ++j) {
        const double e = static_cast<double>(a->outcome(i, dims[j])) - goal[j];
        d += e * e;
      }
      if (d < best_d - 1e-9) {
        best_d = d;
        best_first = best_last = i;
      } else if (d <= best_d + 1e-9) {
        best_last = i;
      }
    }
    float got_d = -1.0f;
    const int first = nearest_neighbour(*a, dims, 3, goal, TieRule::kEarliest, &got_d);
    EXPECT_EQ(first, best_first) << "query " << q;
    EXPECT_NEAR(got_d, best_d, 1e-5) << "query " << q;
    EXPECT_EQ(nearest_neighbour(*a, dims, 3, goal, TieRule::kLatest), best_last) << "query " << q;
  }
}

}  // namespace
}  // namespace curio
