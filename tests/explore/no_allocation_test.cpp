// Proves the exploration core is heap-free: this binary replaces the global allocator with
// counting versions (tests/common/allocation_counter.hpp), then runs a full 10,000-episode
// MGE exploration (init included) on a toy environment.
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>

#include "firmware/explore/explorer.hpp"
#include "firmware/explore/module_layouts.hpp"
#include "tests/common/allocation_counter.hpp"
#include "tests/explore/toy_environment.hpp"

namespace curio {
namespace {

// Kept out of the optimiser's reach so the deliberate allocations below really happen.
void* volatile g_sink = nullptr;

TEST(NoAllocation, CounterSeesDeliberateAllocations) {
  test::start_counting_allocations();
  g_sink = new int(1);
  delete static_cast<int*>(g_sink);
  g_sink = std::malloc(16);
  std::free(g_sink);
  EXPECT_EQ(test::stop_counting_allocations(), 2);
}

TEST(NoAllocation, TenThousandEpisodeMgeRunAllocatesNothing) {
  auto explorer = std::make_unique<Explorer>();  // the one allocation, before counting
  ExplorerConfig config;
  set_efr_modules(config, Algorithm::kMge);
  config.n_bootstrap = 100;
  config.n_episodes = 10000;
  config.seed = 1;

  test::start_counting_allocations();
  Status init = explorer->init(config);
  Status worst = Status::kOk;
  float theta[kThetaDim];
  float outcome[kEfrOutcomeDim];
  int episodes = 0;
  while (!explorer->done() && worst == Status::kOk) {
    Status s = explorer->propose(theta);
    test::toy_outcome(theta, outcome);
    if (s == Status::kOk) s = explorer->observe(outcome);
    if (s != Status::kOk) worst = s;
    ++episodes;
  }
  const long allocations = test::stop_counting_allocations();

  EXPECT_EQ(init, Status::kOk);
  EXPECT_EQ(worst, Status::kOk);
  EXPECT_EQ(episodes, 10100);
  EXPECT_EQ(allocations, 0);
  EXPECT_GT(explorer->counters().nn_queries, 3000u);
}

// The strategy beyond SPEC (frontier goals, σ ladder) keeps the same discipline.
TEST(NoAllocation, TenThousandEpisodeBeyondRunAllocatesNothing) {
  auto explorer = std::make_unique<Explorer>();
  ExplorerConfig config;
  set_efr_modules(config, Algorithm::kMge);
  config.seed = 2;
  config.frontier_share = 0.5f;
  const float ladder[4] = {1, 2, 2, 4};
  for (int i = 0; i < 4; ++i) config.sigma_ladder[i] = ladder[i];

  test::start_counting_allocations();
  Status worst = explorer->init(config);
  float theta[kThetaDim];
  float outcome[kEfrOutcomeDim];
  while (!explorer->done() && worst == Status::kOk) {
    worst = explorer->propose(theta);
    test::toy_outcome(theta, outcome);
    if (worst == Status::kOk) worst = explorer->observe(outcome);
  }
  const long allocations = test::stop_counting_allocations();
  EXPECT_EQ(worst, Status::kOk);
  EXPECT_EQ(explorer->episode(), 10100);
  EXPECT_EQ(allocations, 0);
}

}  // namespace
}  // namespace curio

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
