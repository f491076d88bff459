// Novelty steps of curio-online (online_options.hpp): the options round-trip through
// options.json, runs that predate them resume with them off, bad values are refused, and the
// evaluation-only ball-moved test reads the rest spot, and the worst-reconstructed ranking
// novelty steps draw from. The steps themselves: the Explorer's explore_around tests
// (tests/explore) and online_smoke (a run with them, stop + resume).
#include <gtest/gtest.h>

#include "host_tools/online/goal_space.hpp"
#include "host_tools/online/online_options.hpp"
#include "host_tools/online/online_training.hpp"

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

// Novelty steps draw from these: worst first, ties by lower index.
TEST(NoveltySteps, WorstReconstructedAreTheLargestErrorsWorstFirstTiesByIndex) {
  const std::vector<double> err{5.0, 9.0, 1.0, 9.0, 7.0, 0.5};
  EXPECT_EQ(worst_reconstructed(err, 3), (std::vector<uint32_t>{1, 3, 4}));
  EXPECT_EQ(worst_reconstructed(err, 1), (std::vector<uint32_t>{1}));
  EXPECT_EQ(worst_reconstructed(err, 10), (std::vector<uint32_t>{1, 3, 4, 0, 2, 5}));
  EXPECT_TRUE(worst_reconstructed({}, 4).empty());
}

}  // namespace
}  // namespace curio::online
