// curio-lab on a cluster: the split of a campaign into tasks, the per-run records, the merge
// (complete, partial, refused) and the Slurm scripts written for what is left to run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <tuple>

#include "host_tools/experiment/campaign_json.hpp"
#include "host_tools/experiment/report.hpp"
#include "host_tools/lab/campaign_merge.hpp"
#include "host_tools/lab/campaign_runner.hpp"
#include "host_tools/lab/campaign_task.hpp"
#include "host_tools/lab/local_campaign.hpp"
#include "host_tools/lab/run_record.hpp"
#include "host_tools/lab/slurm_jobs.hpp"

namespace curio::lab {
namespace {
namespace fs = std::filesystem;

CampaignConfig small_campaign(const std::string& name) {
  CampaignConfig c;
  c.algorithms = {"RPE", "MGE-EFR"};
  c.seeds = {0, 1, 2};
  c.sigmas = {0.05, 0.1};
  c.episodes = 200;
  c.threads = 2;
  c.quiet = true;
  c.out_dir = (fs::temp_directory_path() / ("curio_split_test_" + name)).string();
  fs::remove_all(c.out_dir);
  return c;
}

// Runs every task of `c` into DIR/task-I.
void run_all_tasks(CampaignConfig c, int tasks) {
  const std::string root = c.out_dir;
  for (int t = 0; t < tasks; ++t) {
    c.out_dir = root + "/task-" + std::to_string(t);
    TaskOutcome out;
    std::string error;
    ASSERT_TRUE(run_task(c, t, tasks, &out, &error)) << error;
    EXPECT_EQ(out.failed, 0u);
  }
}

// Everything the report reads of a run, compared exactly (== on doubles and floats).
void expect_same_run(const RunResult& a, const RunResult& b) {
  const auto reported = [](const RunResult& r) {
    return std::tie(r.spec.algorithm.name, r.spec.explorer.seed, r.checkpoints, r.ratio, r.grasps,
                    r.final_ball, r.interest, r.interest_episodes, r.module_names, r.module_choices,
                    r.module_latents, r.error);
  };
  EXPECT_TRUE(reported(a) == reported(b)) << run_stem(a.spec) << " vs " << run_stem(b.spec);
  const auto verdict = [](const ModuleVerdict& v) {
    return std::tie(v.exploits, v.mean_progress, v.t, v.mean_interest, v.relative_interest,
                    v.controllable);
  };
  ASSERT_EQ(a.verdicts.size(), b.verdicts.size());
  for (size_t k = 0; k < a.verdicts.size(); ++k)
    EXPECT_TRUE(verdict(a.verdicts[k]) == verdict(b.verdicts[k])) << "module " << k;
}

TEST(CampaignSplit, TasksAreDisjointCoverTheCampaignAndAreStable) {
  for (size_t runs : {1u, 7u, 45u, 270u}) {
    for (int tasks : {1, 2, 5, 15, 300}) {
      std::vector<int> owner(runs, -1);
      for (int t = 0; t < tasks; ++t) {
        const auto mine = task_runs(runs, t, tasks);
        EXPECT_TRUE(std::is_sorted(mine.begin(), mine.end()));
        EXPECT_EQ(mine, task_runs(runs, t, tasks));  // the same on every node, every time
        for (size_t i : mine) {
          ASSERT_LT(i, runs);
          EXPECT_EQ(owner[i], -1) << "run " << i << " in two tasks";
          owner[i] = t;
        }
        EXPECT_LE(mine.size(),
                  (runs + static_cast<size_t>(tasks) - 1) / static_cast<size_t>(tasks));
      }
      EXPECT_EQ(std::count(owner.begin(), owner.end(), -1), 0) << "a run in no task";
    }
  }
  EXPECT_TRUE(task_runs(10, 3, 3).empty());
  EXPECT_TRUE(task_runs(10, -1, 3).empty());
  EXPECT_EQ(task_runs(10, 1, 3), (std::vector<size_t>{1, 4, 7}));
  EXPECT_EQ(tasks_for_chunk(45, 3), 15);
  EXPECT_EQ(tasks_for_chunk(45, 4), 12);
  EXPECT_EQ(tasks_for_chunk(45, 100), 1);
  EXPECT_EQ(tasks_for_chunk(0, 3), 1);
}

TEST(CampaignJson, RoundTripsEveryField) {
  CampaignConfig c = small_campaign("json");
  c.physics = sim::Physics::kOde;
  c.bootstrap = 50;
  c.competence_clip = 1.5;
  c.window = 300;
  c.epsilon = 0.2;
  c.tie_rule = TieRule::kEarliest;
  c.competence_measure = CompetenceMeasure::kScaled;
  c.world.grasp_radius = 0.11;
  c.world.distractor_noise = 0.07;
  std::string error;
  const auto back = campaign_from_json(campaign_to_json(c), &error);
  ASSERT_TRUE(back) << error;
  EXPECT_EQ(campaign_to_json(*back), campaign_to_json(c));
  EXPECT_TRUE(campaign_differences(campaign_to_json(*back), campaign_to_json(c)).empty());
  CampaignConfig d = c;
  d.episodes = 100;
  const auto diff = campaign_differences(campaign_to_json(c), campaign_to_json(d));
  ASSERT_EQ(diff.size(), 1u);
  EXPECT_EQ(diff[0], "episodes: 200 vs 100");
}

// A campaign's strategy beyond SPEC is part of its identity; SPEC's leaves the identity as it
// was before strategies existed (old task folders and summaries stay this campaign's).
TEST(CampaignJson, TheStrategyIsWrittenOnlyWhenItIsNotSpecs) {
  CampaignConfig c = small_campaign("json_explore");
  EXPECT_FALSE(campaign_to_json(c).contains("explore"));
  c.explore = "beyond";
  const nlohmann::json j = campaign_to_json(c);
  EXPECT_EQ(j.at("explore"), "beyond");
  std::string error;
  const auto back = campaign_from_json(j, &error);
  ASSERT_TRUE(back) << error;
  EXPECT_EQ(back->explore, "beyond");
  for (const RunSpec& r : expand_runs(*back)) {
    EXPECT_EQ(r.explorer.frontier_share, 0.5f);
    EXPECT_EQ(r.explorer.sigma_ladder[3], 4.0f);
  }
  nlohmann::json unknown = j;
  unknown["explore"] = "frontier-ish";
  EXPECT_FALSE(campaign_from_json(unknown, &error));
  EXPECT_NE(error.find("frontier-ish"), std::string::npos) << error;
}

// A manifest edited to a value no command line could give is refused, never wrapped or cut.
TEST(CampaignJson, RefusesWhatNoCommandLineCouldGive) {
  const nlohmann::json good = campaign_to_json(small_campaign("json_bad"));
  std::string error;
  ASSERT_TRUE(campaign_from_json(good, &error)) << error;
  const std::pair<const char*, nlohmann::json> bad[] = {
      {"seeds", nlohmann::json::array({0, -1})}, {"seeds", nlohmann::json::array({0.5})},
      {"episodes", 2.5},  {"episodes", 0},  {"episodes", 4294967301ull},  {"bootstrap", -7},  {"grasp_radius", -0.1},
      {"sigmas", nlohmann::json::array({-1.0})}, {"algorithms", nlohmann::json::array({"GOAT"})}};
  for (const auto& [key, value] : bad) {
    nlohmann::json j = good;
    j[key] = value;
    EXPECT_FALSE(campaign_from_json(j, &error)) << key << " = " << value.dump();
    EXPECT_FALSE(error.empty());
  }
}

// A task manifest that was damaged or edited is refused with its path named, never expanded:
// a runs_in_campaign of 10^18 would otherwise ask for 10^18 run indices.
TEST(TaskManifest, ReadsWhatItWroteAndRefusesDamage) {
  const CampaignConfig c = small_campaign("manifest");
  const nlohmann::json good = manifest_json(c, 1, 3);
  std::string error;
  const auto m = parse_task_manifest(good.dump(), "m.json", &error);
  ASSERT_TRUE(m) << error;
  EXPECT_EQ(m->runs, task_runs(expand_runs(c).size(), 1, 3));
  EXPECT_EQ(m->campaign, campaign_to_json(c));
  const std::pair<const char*, nlohmann::json> bad[] = {
      {"runs_in_campaign", 1000000000000000000ull}, {"runs_in_campaign", -1},
      {"task", 3},  {"task", -1},  {"tasks", 0},  {"tasks", 4294967299ull},
      {"runs", nlohmann::json::array({{{"index", 2}}})},  {"campaign", 7},  {"version", 2}};
  for (const auto& [key, value] : bad) {
    nlohmann::json j = good;
    j[key] = value;
    EXPECT_FALSE(parse_task_manifest(j.dump(), "m.json", &error)) << key << " = " << value.dump();
    EXPECT_NE(error.find("m.json"), std::string::npos) << error;
  }
  EXPECT_FALSE(parse_task_manifest("{\"format\": \"curio-lab task\", \"version\": 1", "m.json",
                                   &error));
  EXPECT_FALSE(parse_task_manifest("[]", "m.json", &error));
}

TEST(RunRecord, KeepsEveryNumberExactlyNanIncluded) {
  CampaignConfig c = small_campaign("record");
  const auto specs = expand_runs(c);
  RunResult r = run_exploration(specs[4]);
  ASSERT_TRUE(r.error.empty());
  ASSERT_FALSE(r.verdicts.empty());
  r.verdicts[0].t = std::nan("");
  r.verdicts[0].mean_progress = -0.0;
  fs::create_directories(c.out_dir);
  const std::string path = c.out_dir + "/r.cbor";
  std::string error;
  ASSERT_TRUE(write_run_record(path, 4, r, &error)) << error;
  const auto back = read_run_record(path, 4, specs[4], &error);
  ASSERT_TRUE(back) << error;
  EXPECT_TRUE(std::isnan(back->verdicts[0].t));
  EXPECT_TRUE(std::signbit(back->verdicts[0].mean_progress));
  r.verdicts[0].t = 0;
  RunResult b = *back;
  b.verdicts[0].t = 0;
  expect_same_run(r, b);
  EXPECT_EQ(back->seconds, r.seconds);
  // The record names its run: read as another run it is refused.
  EXPECT_FALSE(read_run_record(path, 5, specs[5], &error));
  EXPECT_NE(error.find("not run 5"), std::string::npos) << error;
  EXPECT_FALSE(read_run_record(c.out_dir + "/none.cbor", 4, specs[4], &error));
}

// A record changed on disk is never read as a result: a ball position edited to another valid
// value (the CBOR still parses) or any byte flipped reads as damaged; a resumed campaign names
// it and runs that run again, ending as if it had never been damaged.
TEST(RunRecord, ADamagedRecordIsRefusedAndItsRunRedone) {
  CampaignConfig c = small_campaign("damaged");
  std::vector<RunResult> clean;
  LocalCampaignOutcome out;
  std::string error;
  ASSERT_EQ(run_local_campaign(c, {}, &clean, &out, &error), LocalCampaignStatus::kOk) << error;
  const auto specs = expand_runs(c);
  const std::string path = record_path(c.out_dir, 1);
  const auto read_bytes = [&] {
    std::ifstream f(path, std::ios::binary);
    return std::vector<uint8_t>{std::istreambuf_iterator<char>(f), {}};
  };
  const auto write_bytes = [&](const std::vector<uint8_t>& b) {
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(b.data()),
                                                static_cast<std::streamsize>(b.size()));
  };
  const std::vector<uint8_t> good = read_bytes();
  // Valid but wrong content: one ball position moved, the record's CRC kept.
  nlohmann::json record = nlohmann::json::from_cbor(good);
  nlohmann::json body = nlohmann::json::from_cbor(record.at("body").get_binary());
  body["final_ball"][0] = 0.5f;
  record["body"] = nlohmann::json::binary(nlohmann::json::to_cbor(body));
  write_bytes(nlohmann::json::to_cbor(record));
  EXPECT_FALSE(read_run_record(path, 1, specs[1], &error));
  EXPECT_NE(error.find("damaged (CRC mismatch)"), std::string::npos) << error;
  // Any single byte flipped: refused one way or another, never read.
  for (size_t at = 0; at < good.size(); at += 7) {
    std::vector<uint8_t> bad = good;
    bad[at] ^= 0x10;
    write_bytes(bad);
    EXPECT_FALSE(read_run_record(path, 1, specs[1], &error)) << "byte " << at << " flipped";
  }
  // The campaign again over the damaged record: named, redone, the same results.
  std::vector<RunResult> again;
  LocalCampaignOutcome out2;
  ASSERT_EQ(run_local_campaign(c, {}, &again, &out2, &error), LocalCampaignStatus::kOk) << error;
  bool named = false;
  for (const auto& n : out2.notes) named |= n.find("damaged") != std::string::npos ||
                                            n.find("unreadable") != std::string::npos;
  EXPECT_TRUE(named) << "no note names the damaged record";
  EXPECT_EQ(out2.skipped, specs.size() - 1);
  ASSERT_EQ(again.size(), clean.size());
  for (size_t i = 0; i < clean.size(); ++i) expect_same_run(again[i], clean[i]);
  EXPECT_TRUE(read_run_record(path, 1, specs[1], &error)) << error;  // rewritten whole
}

TEST(CampaignMerge, EqualsTheLocalCampaignRunForRun) {
  CampaignConfig c = small_campaign("merge");
  run_all_tasks(c, 5);
  double wall = 0;
  const auto local = run_campaign(c, &wall);
  std::string error;
  const auto merged = merge_tasks({c.out_dir}, &error);
  ASSERT_TRUE(merged) << error;
  EXPECT_TRUE(merged->missing.empty());
  EXPECT_TRUE(merged->failed.empty());
  EXPECT_EQ(campaign_to_json(merged->config), campaign_to_json(c));
  ASSERT_EQ(merged->results.size(), local.size());
  for (size_t i = 0; i < local.size(); ++i) expect_same_run(merged->results[i], local[i]);
  // Task folders given one by one, in any order, merge the same.
  const auto again =
      merge_tasks({c.out_dir + "/task-3", c.out_dir + "/task-0", c.out_dir + "/task-1",
                   c.out_dir + "/task-4", c.out_dir + "/task-2"},
                  &error);
  ASSERT_TRUE(again) << error;
  ASSERT_EQ(again->results.size(), local.size());
  for (size_t i = 0; i < local.size(); ++i) expect_same_run(again->results[i], local[i]);
}

TEST(CampaignMerge, ListsMissingRunsAndTasks) {
  CampaignConfig c = small_campaign("partial");
  run_all_tasks(c, 4);
  fs::remove(record_path(c.out_dir + "/task-1", 5));
  fs::remove_all(c.out_dir + "/task-3");
  std::string error;
  const auto merged = merge_tasks({c.out_dir}, &error);
  ASSERT_TRUE(merged) << error;
  // 12 runs; task 3 held 3, 7, 11; task 1 lost 5.
  ASSERT_EQ(merged->missing.size(), 4u);
  EXPECT_NE(merged->missing[0].find("run 3 "), std::string::npos) << merged->missing[0];
  EXPECT_NE(merged->missing[0].find("no folder of task 3"), std::string::npos);
  EXPECT_NE(merged->missing[1].find("run 5 MGE-EFR_sigma0.05_seed2 (task 1)"), std::string::npos)
      << merged->missing[1];
  EXPECT_EQ(merged->results.size(), 8u);
  // Rerunning task 1 runs only the lost run.
  CampaignConfig t1 = c;
  t1.out_dir = c.out_dir + "/task-1";
  EXPECT_EQ(runs_to_do(t1, t1.out_dir, 1, 4), (std::vector<size_t>{5}));
  TaskOutcome out;
  ASSERT_TRUE(run_task(t1, 1, 4, &out, &error)) << error;
  EXPECT_EQ(out.runs, 3u);
  EXPECT_EQ(out.skipped, 2u);
  EXPECT_TRUE(runs_to_do(t1, t1.out_dir, 1, 4).empty());
}

TEST(CampaignMerge, RefusesAnotherCampaignAndNamesTheDifference) {
  CampaignConfig a = small_campaign("mismatch_a");
  CampaignConfig b = small_campaign("mismatch_b");
  b.episodes = 100;
  run_all_tasks(a, 2);
  run_all_tasks(b, 2);
  std::string error;
  EXPECT_FALSE(merge_tasks({a.out_dir + "/task-0", b.out_dir + "/task-1"}, &error));
  EXPECT_NE(error.find("another campaign"), std::string::npos) << error;
  EXPECT_NE(error.find("episodes: 200 vs 100"), std::string::npos) << error;
  // The same campaign split two ways.
  CampaignConfig c = small_campaign("mismatch_c");
  run_all_tasks(c, 3);
  EXPECT_FALSE(merge_tasks({a.out_dir + "/task-0", c.out_dir + "/task-1"}, &error));
  EXPECT_NE(error.find("split two ways"), std::string::npos) << error;
  // The same task twice.
  EXPECT_FALSE(merge_tasks({a.out_dir + "/task-0", a.out_dir + "/task-0"}, &error));
  EXPECT_NE(error.find("task 0 is both"), std::string::npos) << error;
  EXPECT_FALSE(merge_tasks({a.out_dir + "/nothing"}, &error));
  // A task folder refuses to become another campaign's task.
  CampaignConfig other = b;
  other.out_dir = a.out_dir + "/task-0";
  TaskOutcome out;
  EXPECT_FALSE(run_task(other, 0, 2, &out, &error));
  EXPECT_NE(error.find("episodes: 200 vs 100"), std::string::npos) << error;
}

TEST(SlurmJobs, SpecsTimesAndOptions) {
  EXPECT_EQ(array_spec({0, 1, 2, 5, 7, 8}), "0-2,5,7-8");
  EXPECT_EQ(array_spec({3}), "3");
  EXPECT_EQ(slurm_time(1), "0:01:00");
  EXPECT_EQ(slurm_time(3725), "1:03:00");
  EXPECT_EQ(shell_quote("it's"), "'it'\\''s'");
  CampaignConfig c = small_campaign("options");
  c.seeds = {0, 1, 2, 3, 9};
  c.sigmas = {0.05, 0.1};
  const auto o = campaign_run_options(c);
  const auto value = [&](const std::string& key) {
    return *(std::find(o.begin(), o.end(), key) + 1);
  };
  EXPECT_EQ(value("--seeds"), "0-3,9");
  EXPECT_EQ(value("--noise"), "0.05,0.1");
  EXPECT_EQ(value("--algos"), "RPE,MGE-EFR");
  EXPECT_EQ(value("--window"), "1000");
  EXPECT_EQ(value("--epsilon"), "0.1");
  EXPECT_EQ(std::find(o.begin(), o.end(), "--bootstrap"), o.end());  // each algorithm's default
}

TEST(SlurmJobs, TheArrayHoldsOnlyTheTasksLeftToRun) {
  CampaignConfig c = small_campaign("slurm");
  CampaignJobRequest q;
  q.config = c;
  q.run_options = campaign_run_options(c);
  q.out_dir = c.out_dir;
  q.binary = "/opt/curio/curio-lab";
  q.chunk = 4;  // 12 runs: 3 tasks
  q.resources.time = "0:10:00";
  q.resources.job_name = "t";
  SlurmJobFiles f;
  std::string error;
  ASSERT_TRUE(write_campaign_job(q, &f, &error)) << error;
  EXPECT_EQ(f.tasks, 3);
  EXPECT_EQ(f.array, (std::vector<int>{0, 1, 2}));
  std::ifstream in(f.array_script);
  const std::string script{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  EXPECT_NE(script.find("#SBATCH --array=0-2\n"), std::string::npos) << script;
  EXPECT_NE(script.find("--tasks 3 --out '" + c.out_dir + "/tasks/task-'\"$task\""),
            std::string::npos)
      << script;
  CampaignConfig t = c;
  t.out_dir = c.out_dir + "/tasks/task-1";
  TaskOutcome out;
  ASSERT_TRUE(run_task(t, 1, 3, &out, &error)) << error;
  ASSERT_TRUE(write_campaign_job(q, &f, &error)) << error;
  EXPECT_EQ(f.array, (std::vector<int>{0, 2}));
  // Another split of the same folder is refused, naming it.
  q.chunk = 6;
  EXPECT_FALSE(write_campaign_job(q, &f, &error));
  EXPECT_NE(error.find("tasks: 3 vs 2"), std::string::npos) << error;
}

TEST(SlurmJobs, TrainingLeavesOutFinishedSeeds) {
  TrainJobRequest q;
  q.script = "/opt/curio/train.sh";
  q.seeds = {2, 3, 4};
  q.out_dir = (fs::temp_directory_path() / "curio_split_test_train").string();
  fs::remove_all(q.out_dir);
  q.done_file = "4_tuned/done";
  q.resources.time = "2:00:00";
  q.resources.cpus = 2;
  q.resources.job_name = "t";
  fs::create_directories(q.out_dir + "/seed-3/4_tuned");
  std::ofstream(q.out_dir + "/seed-3/4_tuned/done").put('\n');
  SlurmJobFiles f;
  std::string error;
  ASSERT_TRUE(write_train_job(q, &f, &error)) << error;
  EXPECT_EQ(f.array, (std::vector<int>{2, 4}));
  std::ifstream in(f.array_script);
  const std::string script{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  EXPECT_NE(script.find("#SBATCH --array=2,4\n"), std::string::npos) << script;
  EXPECT_NE(script.find("export THREADS=2\n"), std::string::npos) << script;
  EXPECT_NE(
      script.find("exec bash '/opt/curio/train.sh' '" + q.out_dir + "/seed-'\"$seed\" \"$seed\""),
      std::string::npos)
      << script;
}

}  // namespace
}  // namespace curio::lab
