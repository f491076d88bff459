// curio-lab run --out D (local_campaign.hpp): the list of files --replace may remove covers
// every file the report writes, and nothing a user is likely to keep beside it.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include "host_tools/lab/local_campaign.hpp"
#include "host_tools/experiment/report.hpp"
#include "host_tools/lab/scene_log.hpp"

namespace curio::lab {
namespace {
namespace fs = std::filesystem;

TEST(ReportFiles, ListEveryFileTheReportAndTheSceneLogsWrite) {
  CampaignConfig c;
  c.algorithms = {"RPE", "MGE-EFR"};
  c.seeds = {0, 1};
  c.sigmas = {0.05, 0.1};
  c.episodes = 100;
  c.threads = 2;
  c.quiet = true;
  c.save_scenes = true;
  c.out_dir = (fs::temp_directory_path() / "curio_report_files_test").string();
  fs::remove_all(c.out_dir);
  std::vector<RunResult> results;
  LocalCampaignOutcome out;
  std::string error;
  ASSERT_EQ(run_local_campaign(c, {}, &results, &out, &error), LocalCampaignStatus::kOk) << error;
  std::vector<std::string> warnings, written;
  ASSERT_TRUE(
      write_report(c, results, summarize_campaign(c, results, 1.0), &warnings, &error, &written))
      << error;
  const auto listed = report_files(c);
  const std::set<std::string> known(listed.begin(), listed.end());
  // Every file in the folder but the manifest and the records (which --replace removes by the
  // manifest's run list) is one report_files names.
  size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(c.out_dir)) {
    if (!e.is_regular_file()) continue;
    const std::string rel = fs::relative(e.path(), c.out_dir).string();
    if (rel == "manifest.json" || rel.starts_with("records/")) continue;
    ++files;
    EXPECT_TRUE(known.count(rel)) << rel << " is written but not in report_files";
  }
  EXPECT_GE(files, written.size());  // the scene logs besides
  for (const auto& w : written) EXPECT_TRUE(known.count(fs::relative(w, c.out_dir).string())) << w;
  // Only the campaign's own names: nothing of another seed or σ.
  for (const auto& f : listed) {
    EXPECT_EQ(f.find("seed2"), std::string::npos) << f;
    EXPECT_EQ(f.find("sigma0.2"), std::string::npos) << f;
  }
  fs::remove_all(c.out_dir);
}

}  // namespace
}  // namespace curio::lab
