#include "host_tools/lab/run_command.hpp"

#include <cstdio>

#include "host_tools/cli/command_line.hpp"
#include "host_tools/common/output_folder.hpp"
#include "host_tools/experiment/report.hpp"
#include "host_tools/lab/campaign_task.hpp"
#include "host_tools/lab/local_campaign.hpp"
#include "host_tools/lab/print_report.hpp"
#include "host_tools/lab/stop_signals.hpp"

namespace curio::lab {

CLI::App* add_run_command(CLI::App& app, CampaignOptions& campaign, RunCommandOptions& o) {
  auto* run = app.add_subcommand("run", "Run a campaign and write CSV, JSON and PNG results");
  add_campaign_options(run, campaign);
  CampaignConfig& c = campaign.config;
  run->add_option("--out", c.out_dir,
                  "Output folder. Its manifest.json and records/ (one record per finished run) "
                  "make it resumable: a folder holding this same campaign, finished, is not run "
                  "again (the report is rewritten); unfinished, it is resumed (finished runs "
                  "skipped). A folder holding another campaign is refused, naming the "
                  "differences, unless --replace; a non-empty folder holding no campaign is "
                  "refused. One curio-lab or curio-controller writes a folder at a time (a second "
                  "is refused, naming the first). Ctrl-C stops cleanly (exit 130; SIGTERM 143): "
                  "rerun to resume")
      ->check(curio::cli::kOutputFolder)
      ->capture_default_str();
  run->add_flag("--replace", o.replace,
                "Remove the campaign --out holds (only the files curio-lab wrote for it: "
                "records, run CSVs, summaries, plots) and run this one from scratch");
  run->add_flag("--no-journal", o.no_journal,
                "Do not journal the runs in flight (records/run-<i>.journal): a run stopped part "
                "way then starts again from its first episode");
  run->add_flag("--json", o.json, "Print the JSON summary to stdout instead of the table");
  run->add_flag("--quiet", c.quiet, "No progress lines");
  run->add_flag("--save-scenes", c.save_scenes,
                "Also write runs/<run>_scenes.csv: every episode's final ball and distractor "
                "position (training data for curio-train train --scenes)");
  run->add_flag("--print-checksum", c.print_checksum,
                "Print each run's archive checksum on stderr as it finishes (FNV-1a of every "
                "episode's θ and outcome, as curio-controller --print-checksum); runs already "
                "recorded in --out are not run again and print none");
  run->add_option(
      "--task", o.task,
      "Run only task I of --tasks N (the runs i with i mod N = I, in the campaign's "
      "fixed order) into --out as a task folder for `merge`; recorded runs are skipped");
  run->add_option("--tasks", o.tasks, "How many tasks the campaign is split into (with --task)");
  return run;
}

CLI::App* add_paper_command(CLI::App& app, CampaignOptions& campaign, RunCommandOptions& o) {
  auto* paper = app.add_subcommand(
      "paper",
      "The paper's whole figure as one campaign: RPE, RGE-EFR, MGE-EFR, RGE-VAE, MGE-VAE, "
      "RGE-βVAE, MGE-βVAE (+ the 10-module MGE-VAE-10 and MGE-βVAE-10 for the interest plots) "
      "× seeds × σ ∈ {0.05, 0.1}; learned goal spaces need the trained weight headers. "
      "Unless given, --algos is all nine, --seeds 0-14, --noise 0.05,0.1 and --out out/paper "
      "(the defaults printed below are `run`'s)");
  add_campaign_options(paper, campaign);
  paper->add_option("--out", campaign.config.out_dir, "Output folder (resumable, as for run --out)")
      ->check(curio::cli::kOutputFolder)
      ->capture_default_str();
  paper->add_flag("--replace", o.replace, "As for run --replace");
  paper->add_flag("--json", o.json, "Print the JSON summary to stdout instead of the table");
  paper->add_flag("--quiet", campaign.config.quiet, "No progress lines");
  paper->add_flag("--efr-only", o.efr_only,
                  "Only RPE, RGE-EFR, MGE-EFR (no trained weights needed)");
  return paper;
}

namespace {

// The whole campaign on this machine into --out.
int run_local(const CampaignConfig& c, const RunCommandOptions& o) {
  install_stop_handlers();
  LocalCampaignOptions lo;
  lo.replace = o.replace;
  lo.journal = !o.no_journal;
  lo.log = stderr;
  lo.stop = stop_flag();
  std::vector<RunResult> results;
  LocalCampaignOutcome out;
  std::string error;
  const auto claim =
      host::claim_output_folder_or_say("curio-lab", c.out_dir, host::OutputAccess::kExclusive);
  if (!claim) return cli::kRuntimeFailure;
  const auto status = run_local_campaign(c, lo, &results, &out, &error);
  if (status != LocalCampaignStatus::kOk) {
    std::fprintf(stderr, "curio-lab: %s\n", error.c_str());
    return status == LocalCampaignStatus::kRefused ? cli::kUsageError : cli::kRuntimeFailure;
  }
  if (stop_requested()) {
    std::fprintf(stderr,
                 "curio-lab: stopped by %s: %zu of %zu runs finished and recorded in %s/records "
                 "(%zu this time, %zu before); %zu runs not finished. Run the same command again "
                 "to resume (finished runs are skipped), or `curio-lab merge %s --out DIR "
                 "--allow-partial` for a report of the finished ones\n",
                 stop_signal_name(), out.skipped + out.ran, out.runs, c.out_dir.c_str(), out.ran,
                 out.skipped, out.runs - out.skipped - out.ran, c.out_dir.c_str());
    return stopped_exit_code();
  }
  return write_and_print_report(c, results, summarize_campaign(c, results, out.wall_seconds),
                                out.wall_seconds, {.json = o.json, .scenes_written = true});
}

// `run --task I --tasks N`: only slice I of N, into a task folder for `merge`.
int run_task_share(const CampaignConfig& c, int task, int tasks) {
  install_stop_handlers();
  TaskOutcome out;
  std::string error;
  // The tasks of one campaign share the folder (each writes its own records); a whole-campaign
  // writer (run without --task, merge) excludes them.
  const auto claim =
      host::claim_output_folder_or_say("curio-lab", c.out_dir, host::OutputAccess::kShared);
  if (!claim) return cli::kRuntimeFailure;
  const bool ok = run_task(c, task, tasks, &out, &error, stop_flag());
  for (const auto& r : out.redone) std::fprintf(stderr, "curio-lab: %s\n", r.c_str());
  if (!ok) {
    std::fprintf(stderr, "curio-lab: %s\n", error.c_str());
    return cli::kRuntimeFailure;
  }
  if (stop_requested()) {
    std::fprintf(stderr,
                 "curio-lab: stopped by %s: task %d of %d has %zu of %zu runs recorded in "
                 "%s/records; run it again to resume (recorded runs are skipped)\n",
                 stop_signal_name(), task, tasks, out.runs - out.stopped, out.runs,
                 c.out_dir.c_str());
    return stopped_exit_code();
  }
  std::printf(
      "task %d of %d: %zu runs (%zu already recorded, skipped; %zu failed) in %.1f s; "
      "records in %s/\n",
      task, tasks, out.runs, out.skipped, out.failed, out.wall_seconds, c.out_dir.c_str());
  return out.failed == 0 ? 0 : 1;
}

}  // namespace

int run_command(const CLI::App& command, const CampaignOptions& campaign,
                const RunCommandOptions& o) {
  CampaignConfig c;
  std::string problem;
  if (!build_campaign(campaign, &c, &problem)) return cli::usage_error(command, problem);
  if (o.tasks <= 0 && o.task < 0) return run_local(c, o);
  if (o.tasks < 1 || o.task < 0 || o.task >= o.tasks)
    return cli::usage_error(command, "--task must be in [0, --tasks) (got " +
                                         std::to_string(o.task) + " of " + std::to_string(o.tasks) +
                                         ")");
  if (o.replace)
    return cli::usage_error(command,
                            "--replace is for a local run; a task folder of another campaign is "
                            "refused (use another --out)");
  return run_task_share(c, o.task, o.tasks);
}

int paper_command(const CLI::App& command, CampaignOptions campaign, const RunCommandOptions& o) {
  if (command.get_option("--algos")->count() == 0)
    campaign.algos = o.efr_only ? "RPE,RGE-EFR,MGE-EFR"
                                : "RPE,RGE-EFR,MGE-EFR,RGE-VAE,MGE-VAE,RGE-βVAE,MGE-βVAE,"
                                  "MGE-VAE-10,MGE-βVAE-10";
  if (command.get_option("--seeds")->count() == 0) campaign.seeds = "0-14";
  if (command.get_option("--noise")->count() == 0) campaign.exploration.noise = "0.05,0.1";
  if (command.get_option("--out")->count() == 0) campaign.config.out_dir = "out/paper";
  CampaignConfig c;
  std::string problem;
  if (!build_campaign(campaign, &c, &problem)) return cli::usage_error(command, problem);
  return run_local(c, o);
}

}  // namespace curio::lab
