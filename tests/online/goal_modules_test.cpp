// The goal modules of curio-online (--goal-modules, online_options.hpp; goal_space.hpp): open
// modules cover exactly the open latents, singles or groups, in the given order; the explorer
// accepts the config built from them; the option is checked, round-trips through
// options.json, and runs that predate it resume with the old layout ("groups"); the goal scale
// (--goal-scale) reaches the explorer's modules and defaults to the prior for older runs.
#include <array>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "firmware/explore/explorer.hpp"
#include "host_tools/online/goal_space.hpp"
#include "host_tools/online/online_options.hpp"

namespace curio::online {
namespace {

using Modules = std::vector<std::vector<int>>;

TEST(GoalModules, OpenSinglesAreTheOpenLatentsInTheGivenOrder) {
  // KL order of a run with 4 open latents: the held z4..z9 come last, but the filter must not
  // rely on that (here z5 sits between open ones).
  const std::array<uint8_t, 10> order{3, 5, 0, 2, 1, 4, 6, 7, 8, 9};
  EXPECT_EQ(open_modules(order, 4, 1), (Modules{{3}, {0}, {2}, {1}}));
  EXPECT_EQ(open_modules(order, 2, 1), (Modules{{0}, {1}}));
}

TEST(GoalModules, OpenGroupsKeepTheGroupOrdersPairs) {
  const std::array<double, 10> kl{0.1, 3.0, 2.0, 1.9, 0, 0, 0, 0, 0, 0};
  EXPECT_EQ(open_modules(group_order(kl, 2), 4, 2), (Modules{{2, 3}, {1, 0}}));
  EXPECT_EQ(open_modules(group_order(kl, 2), 10, 2).size(), 5u);
}

TEST(GoalModules, OpenModulesRefuseCountsThatDoNotSplit) {
  const std::array<uint8_t, 10> order{0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  EXPECT_THROW(open_modules(order, 3, 2), std::runtime_error);
  EXPECT_THROW(open_modules(order, 0, 1), std::runtime_error);
  EXPECT_THROW(open_modules(order, 11, 1), std::runtime_error);
  EXPECT_THROW(open_modules(order, 4, 0), std::runtime_error);
}

TEST(GoalModules, ConfigOfModulesIsWhatTheExplorerRuns) {
  ExplorerConfig base;
  base.n_bootstrap = 10;
  base.n_episodes = 20;
  const ExplorerConfig c = goal_space_config(base, Modules{{3}, {0}, {2}, {1}});
  EXPECT_EQ(c.n_modules, 4);
  EXPECT_EQ(c.outcome_dim, kLatentDim);
  EXPECT_EQ(c.goal_kind, GoalKind::kClippedNormal);
  EXPECT_EQ(module_latents(c), (Modules{{3}, {0}, {2}, {1}}));
  static Explorer explorer;  // ~680 KB: never on the stack
  ASSERT_EQ(explorer.init(c), Status::kOk);
  EXPECT_EQ(explorer.n_modules(), 4);
  EXPECT_EQ(explorer.goal_module(0).n_dims, 1);
  EXPECT_EQ(explorer.goal_module(0).dims[0], 3);
  EXPECT_THROW(goal_space_config(base, Modules{}), std::runtime_error);
  EXPECT_THROW(goal_space_config(base, Modules{{10}}), std::runtime_error);
  EXPECT_THROW(goal_space_config(base, Modules{{1, 1}}), std::runtime_error);  // repeated latent
}

TEST(GoalModules, OptionIsCheckedAndOldRunsKeepGroups) {
  OnlineOptions o;
  o.nats_per_latent = 3.0;
  o.goal_modules = "open-singles";
  EXPECT_TRUE(check(o).empty());
  EXPECT_TRUE(o.open_goal_modules());
  EXPECT_EQ(o.goal_module_size(), 1);
  auto j = to_json(o);
  EXPECT_EQ(options_from_json(j).goal_modules, "open-singles");
  j.erase("goal_modules");
  EXPECT_EQ(options_from_json(j).goal_modules, "groups");
  EXPECT_FALSE(options_from_json(j).open_goal_modules());
  o.goal_modules = "open-groups";
  EXPECT_EQ(o.goal_module_size(), 2);
  EXPECT_TRUE(check(o).empty());
  o.goal_modules = "pairs";
  EXPECT_FALSE(check(o).empty());
  o.goal_modules = "open-singles";
  o.nats_per_latent = 0.0;  // every latent open: nothing to leave out
  EXPECT_FALSE(check(o).empty());
}

TEST(GoalModules, GoalScaleReachesTheExplorerAndOldRunsKeepThePrior) {
  OnlineOptions o;
  EXPECT_EQ(o.goal_scale, 1.0);
  o.goal_scale = 2.5;
  EXPECT_TRUE(check(o).empty());
  auto j = to_json(o);
  EXPECT_EQ(options_from_json(j).goal_scale, 2.5);
  j.erase("goal_scale");
  EXPECT_EQ(options_from_json(j).goal_scale, 1.0);
  o.goal_scale = 0.0;
  EXPECT_FALSE(check(o).empty());
  ExplorerConfig base;
  base.n_bootstrap = 10;
  base.n_episodes = 20;
  base.goal_scale = 2.5f;
  const ExplorerConfig c = goal_space_config(base, Modules{{2, 3}, {0, 1}});
  EXPECT_EQ(c.goal_scale, 2.5f);
  static Explorer explorer;  // ~680 KB: never on the stack
  ASSERT_EQ(explorer.init(c), Status::kOk);
  EXPECT_EQ(explorer.goal_module(1).goal_scale, 2.5f);
}

}  // namespace
}  // namespace curio::online
