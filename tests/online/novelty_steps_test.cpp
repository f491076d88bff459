// Novelty steps of curio-online (online_options.hpp): the options round-trip through
// options.json, runs that predate them resume with them off, bad values are refused, and the
// evaluation-only ball-moved test reads the rest spot. The steps themselves: the Explorer's
// explore_around tests (tests/explore) and online_smoke (a run with them, stop + resume).
#include <gtest/gtest.h>

#include "host_tools/online/goal_space.hpp"
#include "host_tools/online/online_options.hpp"

namespace curio::online {
namespace {

TEST(NoveltySteps, OptionsRoundTripAndOldRunsResumeWithThemOff) {
  OnlineOptions o;
  o.novelty_fraction = 0.3;
  o.novelty_top = 0.05;
  auto j = to_json(o);
  EXPECT_EQ(options_from_json(j).novelty_fraction, 0.3);
  EXPECT_EQ(options_from_json(j).novelty_top, 0.05);
  j.erase("novelty_fraction");
  j.erase("novelty_top");
  EXPECT_EQ(options_from_json(j).novelty_fraction, 0.0);
  EXPECT_EQ(options_from_json(j).novelty_top, 0.02);
  EXPECT_TRUE(check(o).empty());
  o.novelty_fraction = 1.5;
  EXPECT_FALSE(check(o).empty());
  o.novelty_fraction = 0.3;
  o.novelty_top = 0.0;
  EXPECT_FALSE(check(o).empty());
}

TEST(NoveltySteps, BallMovedReadsTheRestSpot) {
  EXPECT_FALSE(ball_moved({0.6f, 0.6f, 0.1f, 0.2f}));
  EXPECT_FALSE(ball_moved({0.6005f, 0.5995f, -0.7f, 0.3f}));
  EXPECT_TRUE(ball_moved({0.6f, 0.59f, 0.6f, 0.6f}));
  EXPECT_TRUE(ball_moved({-0.2f, 0.6f, 0.6f, 0.6f}));
}

}  // namespace
}  // namespace curio::online
