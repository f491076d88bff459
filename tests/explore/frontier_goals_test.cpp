// Frontier goals (firmware/explore/frontier_goals.hpp) and the strategies built on them: goals
// land only in unreached cells next to reached ones, cells that keep being missed fade, and an
// Explorer with the ingredients stays deterministic, heap-free and regenerates every θ.
#include "firmware/explore/frontier_goals.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "firmware/explore/explorer.hpp"
#include "firmware/explore/module_layouts.hpp"
#include "tests/explore/toy_environment.hpp"

namespace curio {
namespace {

constexpr float kCell = 2.0f / kFrontierCells;  // a uniform-box module's cell

int cell_index(float v) { return static_cast<int>(std::floor((v + 1.0f) / kCell)); }

GoalModule box_module(int dims) {
  GoalModule m;
  m.n_dims = dims;
  for (int j = 0; j < dims; ++j) m.dims[j] = static_cast<uint8_t>(j);
  return m;
}

// A frontier over one two-dimensional uniform-box module, nothing reached yet.
std::unique_ptr<FrontierGoals> box_frontier() {
  const GoalModule m = box_module(2);
  auto f = std::make_unique<FrontierGoals>();
  f->reset(&m, 1);
  return f;
}

TEST(FrontierGoals, GoalsLieInTheUnreachedRingAroundWhatWasReached) {
  auto f = box_frontier();
  Prng rng(3, 5);
  float goal[2];
  EXPECT_FALSE(f->sample(0, rng, goal)) << "nothing reached: no frontier";
  const float reached[2] = {0.01f, 0.01f};
  f->observe(0, reached);
  EXPECT_EQ(f->reached_cells(0), 1);
  const int rx = cell_index(reached[0]), ry = cell_index(reached[1]);
  int seen[3][3] = {};
  for (int i = 0; i < 2000; ++i) {
    ASSERT_TRUE(f->sample(0, rng, goal));
    const int dx = cell_index(goal[0]) - rx, dy = cell_index(goal[1]) - ry;
    ASSERT_TRUE(std::abs(dx) <= 1 && std::abs(dy) <= 1 && (dx != 0 || dy != 0))
        << goal[0] << ", " << goal[1];
    ++seen[dy + 1][dx + 1];
  }
  for (int dy = 0; dy < 3; ++dy)
    for (int dx = 0; dx < 3; ++dx)
      if (dx != 1 || dy != 1) {
        EXPECT_GT(seen[dy][dx], 150) << "all 8 neighbours drawn alike";
      }
}

TEST(FrontierGoals, CellsThatKeepBeingMissedFade) {
  auto f = box_frontier();
  Prng rng(4, 5);
  float goal[2];
  const float a[2] = {-0.5f, -0.5f};
  f->observe(0, a);
  for (int i = 0; i < 400; ++i) {  // every step aimed at a's ring misses
    ASSERT_TRUE(f->sample(0, rng, goal));
    f->step_done(0);
  }
  const float b[2] = {0.5f, 0.5f};  // something new is reached far away
  f->observe(0, b);
  int near_b = 0;
  for (int i = 0; i < 1000; ++i) {
    ASSERT_TRUE(f->sample(0, rng, goal));
    near_b += std::fabs(goal[0] - b[0]) < 2 * kCell && std::fabs(goal[1] - b[1]) < 2 * kCell;
  }
  EXPECT_GT(near_b, 900) << "the missed ring weighs 1/(1+misses)^2";
}

TEST(FrontierGoals, OnlyModulesOfOneOrTwoDimensionsHaveAGrid) {
  GoalModule modules[3] = {box_module(1), box_module(2), box_module(3)};
  auto f = std::make_unique<FrontierGoals>();
  f->reset(modules, 3);
  EXPECT_TRUE(f->has_grid(0));
  EXPECT_TRUE(f->has_grid(1));
  EXPECT_FALSE(f->has_grid(2));
  const float p[3] = {0.0f, 0.0f, 0.0f};
  f->observe(0, p);
  f->observe(2, p);
  Prng rng(5, 5);
  float goal[3] = {};
  ASSERT_TRUE(f->sample(0, rng, goal));  // 1-D: the cells left and right
  EXPECT_EQ(std::abs(cell_index(goal[0]) - cell_index(0.0f)), 1);
  EXPECT_FALSE(f->sample(2, rng, goal));
}

ExplorerConfig beyond_config(uint64_t seed) {
  ExplorerConfig c;
  set_efr_modules(c, Algorithm::kMge);
  c.n_bootstrap = 100;
  c.n_episodes = 10000;
  c.seed = seed;
  c.frontier_share = 0.5f;
  const float ladder[4] = {1, 2, 2, 4};
  std::memcpy(c.sigma_ladder, ladder, sizeof ladder);
  return c;
}

// Every proposed θ; the explorer is left done.
std::vector<float> run_toy(Explorer& e) {
  std::vector<float> proposed;
  float theta[kThetaDim], outcome[4];
  while (!e.done()) {
    EXPECT_EQ(e.propose(theta), Status::kOk);
    proposed.insert(proposed.end(), theta, theta + kThetaDim);
    test::toy_outcome(theta, outcome);
    EXPECT_EQ(e.observe(outcome), Status::kOk);
  }
  return proposed;
}

TEST(BeyondStrategy, DeterministicRegeneratesEveryThetaAndDiffersFromSpec) {
  auto a = std::make_unique<Explorer>(), b = std::make_unique<Explorer>();
  auto spec = std::make_unique<Explorer>();
  ASSERT_EQ(a->init(beyond_config(9)), Status::kOk);
  ASSERT_EQ(b->init(beyond_config(9)), Status::kOk);
  ExplorerConfig plain = beyond_config(9);
  plain.frontier_share = 0.0f;
  for (float& v : plain.sigma_ladder) v = 0.0f;
  ASSERT_EQ(spec->init(plain), Status::kOk);
  const std::vector<float> pa = run_toy(*a), pb = run_toy(*b), ps = run_toy(*spec);
  ASSERT_EQ(pa.size(), 10100u * kThetaDim);
  EXPECT_EQ(std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(float)), 0);
  EXPECT_NE(std::memcmp(pa.data(), ps.data(), pa.size() * sizeof(float)), 0);
  float theta[kThetaDim];  // the ladder's σ goes through the archive's regeneration too
  for (int i = 0; i < a->archive().size(); ++i) {
    a->archive().theta(i, theta);
    ASSERT_EQ(std::memcmp(theta, &pa[static_cast<size_t>(i) * kThetaDim], sizeof theta), 0)
        << "episode " << i;
  }
}

TEST(BeyondStrategy, IngredientsOutOfRangeAreRefused) {
  auto e = std::make_unique<Explorer>();
  ExplorerConfig c = beyond_config(1);
  c.frontier_share = 1.5f;
  EXPECT_EQ(e->init(c), Status::kInvalidConfig);
  c = beyond_config(1);
  c.sigma_ladder[2] = -1.0f;
  EXPECT_EQ(e->init(c), Status::kInvalidConfig);
  c = beyond_config(1);
  c.sigma_ladder[0] = 0.0f;  // set, but one step would not move
  EXPECT_EQ(e->init(c), Status::kInvalidConfig);
  c.sigma_ladder[0] = NAN;
  EXPECT_EQ(e->init(c), Status::kInvalidConfig);
  EXPECT_EQ(e->init(beyond_config(1)), Status::kOk);
}

TEST(ThetaGenerator, ALadderScalesNoiseNumberXBySigmaTimesLadderXMod4) {
  const float ladder[4] = {1, 2, 2, 4};
  ThetaGenerator flat, stepped;
  flat.reset(17, 0.05f);
  stepped.reset(17, 0.05f, ladder);
  for (uint32_t x = 0; x < 12; ++x) {
    float a[kThetaDim] = {}, b[kThetaDim] = {};
    ThetaGenerator scaled;
    scaled.reset(17, 0.05f * ladder[x % 4]);
    scaled.add_noise(x, a);
    stepped.add_noise(x, b);
    ASSERT_EQ(std::memcmp(a, b, sizeof a), 0) << "x = " << x;
    if (x % 4 == 0) {
      std::memset(a, 0, sizeof a);
      flat.add_noise(x, a);
      std::memset(b, 0, sizeof b);
      stepped.add_noise(x, b);
      EXPECT_EQ(std::memcmp(a, b, sizeof a), 0) << "ladder 1 is σ";
    }
  }
}

}  // namespace
}  // namespace curio
