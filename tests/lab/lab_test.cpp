// curio-lab: the metric, the statistics, the campaign validation and the run recorder.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>

#include "host_tools/cli/seed_text.hpp"
#include "host_tools/experiment/checkpoints.hpp"
#include "host_tools/experiment/exploration_ratio.hpp"
#include "host_tools/experiment/report.hpp"
#include "host_tools/experiment/statistics.hpp"
#include "host_tools/lab/campaign_runner.hpp"

namespace curio::lab {
namespace {

TEST(CompetenceMeasure, ParsesTheNamesItPrintsAndNothingElse) {
  for (const auto m : {CompetenceMeasure::kClipped, CompetenceMeasure::kScaled})
    EXPECT_EQ(parse_competence_measure(to_string(m)), m);
  EXPECT_EQ(parse_competence_measure("cap"), std::nullopt);
  EXPECT_EQ(parse_competence_measure(""), std::nullopt);
}

TEST(ExplorationRatio, CountsEachOfTheNineHundredCellsOnce) {
  ExplorationRatio m;
  EXPECT_EQ(m.ratio(), 0.0);
  m.add(0.6, 0.6);
  m.add(0.61, 0.61);  // same cell: cells are 2/30 ≈ 0.0667 wide
  EXPECT_EQ(m.visited_cells(), 1);
  m.add(-1.0, -1.0);  // corners belong to the first and last cells
  m.add(1.0, 1.0);
  EXPECT_EQ(m.visited_cells(), 3);
  EXPECT_DOUBLE_EQ(m.ratio(), 3.0 / 900.0);
  m.add(1.0001, 0.0);  // outside the grid: no cell
  m.add(std::nan(""), 0.0);
  EXPECT_EQ(m.visited_cells(), 3);
}

TEST(ExplorationRatio, CellBoundaries) {
  EXPECT_EQ(ExplorationRatio::cell_of(-1.0), 0);
  EXPECT_EQ(ExplorationRatio::cell_of(-1.0 + 2.0 / 30 - 1e-12), 0);
  EXPECT_EQ(ExplorationRatio::cell_of(-1.0 + 2.0 / 30 + 1e-12), 1);
  EXPECT_EQ(ExplorationRatio::cell_of(0.0), 15);
  EXPECT_EQ(ExplorationRatio::cell_of(1.0), 29);
  EXPECT_EQ(ExplorationRatio::cell_of(-1.5), -1);
}

TEST(Checkpoints, SpecCheckpointsAreFloorOfIThirtiethsOfTenThousand) {
  const auto c = spec_checkpoints(10100);
  ASSERT_EQ(c.size(), 30u);
  EXPECT_EQ(c[0], 0);
  EXPECT_EQ(c[1], 333);
  EXPECT_EQ(c[2], 666);
  EXPECT_EQ(c[29], 9666);
  const auto curve = curve_checkpoints(10100);
  EXPECT_EQ(curve.back(), 10100);
  EXPECT_TRUE(std::is_sorted(curve.begin(), curve.end()));
  EXPECT_NE(std::find(curve.begin(), curve.end(), 9666), curve.end());
  EXPECT_NE(std::find(curve.begin(), curve.end(), 5000), curve.end());
}

TEST(Statistics, MeanStdAndStudentInterval) {
  const std::vector<double> v = {1.0, 2.0, 3.0, 4.0};
  const Summary s = summarize(v);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_NEAR(s.std, 1.2909944487, 1e-9);
  // t(0.975, 3) = 3.182: half-width 3.182 · 1.29099 / 2
  EXPECT_NEAR(s.ci95_high - s.mean, 3.182 * 1.2909944487 / 2.0, 1e-9);
  EXPECT_NEAR(s.mean - s.ci95_low, s.ci95_high - s.mean, 1e-12);
  EXPECT_DOUBLE_EQ(student_t_975(14), 2.145);
  const Summary one = summarize(std::vector<double>{0.3});
  EXPECT_EQ(one.std, 0.0);
  EXPECT_EQ(one.ci95_low, 0.3);
}

TEST(Seeds, ParsesRangesAndListsAndRejectsNonsense) {
  std::string err;
  EXPECT_EQ(parse_seeds("0-14", &err)->size(), 15u);
  EXPECT_EQ(*parse_seeds("1-3,8", &err), (std::vector<uint64_t>{1, 2, 3, 8}));
  EXPECT_EQ(*parse_seeds("7", &err), (std::vector<uint64_t>{7}));
  for (const char* bad : {"", "a", "3-1", "1,1", "-2", "1-", "1,,2", "+3", " 3", "0x10"}) {
    EXPECT_FALSE(parse_seeds(bad, &err).has_value()) << bad;
    EXPECT_FALSE(err.empty());
  }
}

// Seeds are whole 64-bit numbers in every program: the top of the range is a seed, one more is
// refused, not clamped or wrapped, and a range ending at 2^64 - 1 stops there.
TEST(Seeds, AreTheWhole64BitRangeAndNothingBeyond) {
  std::string err;
  EXPECT_EQ(*parse_seeds("4294967296", &err), (std::vector<uint64_t>{4294967296ULL}));
  EXPECT_EQ(*parse_seeds("18446744073709551614-18446744073709551615", &err),
            (std::vector<uint64_t>{18446744073709551614ULL, 18446744073709551615ULL}));
  for (const char* bad : {"18446744073709551616", "99999999999999999999", "0-18446744073709551616"})
    EXPECT_FALSE(parse_seeds(bad, &err).has_value()) << bad;
  EXPECT_FALSE(parse_seeds("0-18446744073709551615", &err).has_value());  // too many, at once
  EXPECT_NE(err.find("at most"), std::string::npos) << err;
  EXPECT_EQ(curio::cli::parse_seed("18446744073709551615"), UINT64_MAX);
  EXPECT_EQ(curio::cli::parse_seed("-1"), std::nullopt);
  EXPECT_EQ(curio::cli::parse_seed("00042"), 42u);
}

TEST(Campaign, RefusesInvalidConfigurationsBeforeAnyWork) {
  CampaignConfig ok;
  EXPECT_TRUE(validate_campaign(ok).empty());

  CampaignConfig c;
  c.algorithms = {"MGE-EFR", "NOPE"};
  c.sigmas = {-0.1, std::numeric_limits<double>::infinity()};
  c.episodes = -5;
  c.competence_clip = 0.0;
  const auto problems = validate_campaign(c);
  auto mentions = [&](const std::string& what) {
    for (const auto& p : problems)
      if (p.find(what) != std::string::npos) return true;
    return false;
  };
  EXPECT_TRUE(mentions("unknown algorithm 'NOPE'"));
  EXPECT_TRUE(mentions("--noise: σ must be a finite number ≥ 0 (got -0.1)"));
  EXPECT_TRUE(mentions("--noise: σ must be a finite number ≥ 0 (got inf)"));
  EXPECT_TRUE(mentions("--episodes"));
  EXPECT_TRUE(mentions("competence-clip"));

  CampaignConfig big;
  big.episodes = (kArchiveCapacity / 5) * 5;  // + 100 bootstrap does not fit
  const auto p = validate_campaign(big);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_NE(p[0].find("archive capacity"), std::string::npos);
}

RunSpec short_run(const char* algo, uint64_t seed) {
  RunSpec s;
  s.algorithm = *find_algorithm(algo);
  s.explorer.seed = seed;
  s.explorer.n_bootstrap = 100;
  s.explorer.n_episodes = 1500;
  s.explorer.competence_cap = 1.0f;
  return s;
}

TEST(Run, SameSeedSameResultsBitForBit) {
  const RunResult a = run_exploration(short_run("MGE-EFR", 4));
  const RunResult b = run_exploration(short_run("MGE-EFR", 4));
  const RunResult c = run_exploration(short_run("MGE-EFR", 5));
  ASSERT_TRUE(a.error.empty()) << a.error;
  EXPECT_EQ(a.final_ball, b.final_ball);
  EXPECT_EQ(a.ratio, b.ratio);
  EXPECT_EQ(a.interest, b.interest);
  EXPECT_NE(a.final_ball, c.final_ball);
}

TEST(Run, RecordsEveryEpisodeAndAMonotoneRatio) {
  const RunResult r = run_exploration(short_run("MGE-EFR", 1));
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.final_ball.size(), 1600u);
  EXPECT_EQ(r.checkpoints.back(), 1600);
  EXPECT_TRUE(std::is_sorted(r.ratio.begin(), r.ratio.end()));
  EXPECT_TRUE(std::is_sorted(r.grasps.begin(), r.grasps.end()));
  EXPECT_EQ(r.ratio.front(), 0.0);
  EXPECT_GT(r.ratio.back(), 0.0);
  // Interest is recorded for both modules (distractor, ball); each module chosen at least once.
  ASSERT_FALSE(r.interest.empty());
  EXPECT_EQ(r.interest.front().size(), 2u);
  EXPECT_EQ(r.module_choices.size(), 2u);
  EXPECT_GT(r.module_choices[0], 0);
  EXPECT_GT(r.module_choices[1], 0);
  // The ball never leaves the reachable disc (or its start position).
  for (const auto& p : r.final_ball) EXPECT_LE(std::hypot(p[0], p[1]), 1.0 + 1e-6);
}

TEST(Run, GoalExplorationBeatsRandomParametersOnTheBall) {
  // The paper's first claim, on a short budget: MGE-EFR covers more cells than RPE.
  double mge = 0, rpe = 0;
  for (uint64_t seed = 0; seed < 4; ++seed) {
    mge += run_exploration(short_run("MGE-EFR", seed)).ratio.back();
    rpe += run_exploration(short_run("RPE", seed)).ratio.back();
  }
  EXPECT_GT(mge, 1.5 * rpe);
}

TEST(Report, WritesCsvJsonAndTable) {
  CampaignConfig c;
  c.algorithms = {"RPE", "MGE-EFR"};
  c.seeds = {0, 1};
  c.episodes = 500;
  c.threads = 2;
  c.quiet = true;
  c.out_dir = (std::filesystem::temp_directory_path() / "curio_lab_report_test").string();
  std::filesystem::remove_all(c.out_dir);
  double wall = 0;
  const auto results = run_campaign(c, &wall);
  ASSERT_EQ(results.size(), 4u);
  const auto summary = summarize_campaign(c, results, wall);
  std::vector<std::string> warnings;
  std::string error;
  ASSERT_TRUE(write_report(c, results, summary, &warnings, &error)) << error;
  namespace fs = std::filesystem;
  EXPECT_TRUE(fs::exists(fs::path(c.out_dir) / "summary.json"));
  EXPECT_TRUE(fs::exists(fs::path(c.out_dir) / "runs" / "MGE-EFR_sigma0.05_seed1.csv"));
  EXPECT_TRUE(fs::exists(fs::path(c.out_dir) / "runs" / "MGE-EFR_sigma0.05_seed1_interest.csv"));
  ASSERT_EQ(summary["results"].size(), 2u);
  const auto& row = summary["results"][1];
  EXPECT_EQ(row["algorithm"], "MGE-EFR");
  EXPECT_EQ(row["seeds"], 2);
  const auto& last = row["checkpoints"].back();
  EXPECT_EQ(last["episodes"], 600);
  EXPECT_LE(last["ci95"][0].get<double>(), last["mean"].get<double>());
  const std::string table = format_table(summary);
  EXPECT_NE(table.find("| MGE-EFR | 0.05 | 2 |"), std::string::npos);
  // SPEC §4's MGE-EFR row at all four checkpoints, under ours.
  EXPECT_NE(table.find("| ↳ SPEC §4 reference | 0.05 | 15 | 0.184 ± 0.051 | 0.445 ± 0.088 | "
                       "0.576 ± 0.089 | 0.693 ± 0.083 |"),
            std::string::npos)
      << table;
  if (warnings.empty()) {
    EXPECT_TRUE(fs::exists(fs::path(c.out_dir) / "ratio_sigma0.05.png"));
  }
}

}  // namespace
}  // namespace curio::lab
