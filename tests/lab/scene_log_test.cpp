// curio-lab's scene log: every episode's final scene, in the CSV curio-train --scenes reads.
#include <gtest/gtest.h>

#include <cstdlib>
#include <sstream>
#include <string>

#include "firmware/explore/explorer.hpp"
#include "firmware/explore/module_layouts.hpp"
#include "host_tools/experiment/simulated_run.hpp"
#include "host_tools/lab/scene_log.hpp"

namespace curio::lab {
namespace {

TEST(SceneLog, OneRowPerEpisodeHoldingTheScenesTheArchiveRecorded) {
  RunSpec spec;
  spec.algorithm = *find_algorithm("MGE-EFR");
  spec.explorer.n_bootstrap = 100;
  spec.explorer.n_episodes = 200;
  spec.explorer.competence_cap = 1.0f;
  std::vector<std::array<float, 4>> archived;  // EFR outcomes: distractor x, y, ball x, y
  const RunResult r = run_exploration(spec, nullptr, [&](const Explorer& e) {
    for (int i = 0; i < e.archive().size(); ++i)
      archived.push_back({e.archive().outcome(i, kEfrBallX), e.archive().outcome(i, kEfrBallY),
                          e.archive().outcome(i, kEfrDistractorX),
                          e.archive().outcome(i, kEfrDistractorY)});
  });
  ASSERT_TRUE(r.error.empty()) << r.error;
  ASSERT_EQ(archived.size(), 300u);

  std::istringstream csv(scenes_csv(r));
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  EXPECT_EQ(line, "episode,ball_x,ball_y,distractor_x,distractor_y");
  size_t rows = 0, distractor_moves = 0;
  for (; std::getline(csv, line); ++rows) {
    ASSERT_LT(rows, archived.size());
    std::istringstream fields(line);
    std::string field;
    std::getline(fields, field, ',');
    EXPECT_EQ(std::stoul(field), rows);
    for (size_t k = 0; k < 4; ++k) {
      ASSERT_TRUE(std::getline(fields, field, ',')) << line;
      EXPECT_EQ(std::strtof(field.c_str(), nullptr), archived[rows][k]) << "row " << rows;
    }
    if (rows > 0 && archived[rows][2] != archived[rows - 1][2]) ++distractor_moves;
  }
  EXPECT_EQ(rows, 300u);
  EXPECT_GT(distractor_moves, 250u);  // the distractor walks every episode
}

}  // namespace
}  // namespace curio::lab
