#include "host_tools/lab/slurm_command.hpp"

#include <cstdio>
#include <filesystem>
#include <optional>

#include "host_tools/cli/command_line.hpp"

namespace curio::lab {

namespace {

void add_slurm_options(CLI::App* sub, SlurmCommandOptions& o) {
  sub->add_option("--out", o.out, "Output folder (on the shared filesystem)")
      ->required()
      ->check(curio::cli::kOutputFolder);
  sub->add_option("--cpus", o.resources.cpus, "CPUs per array task")->capture_default_str();
  sub->add_option("--time", o.resources.time, "Time limit per array task (Slurm syntax)");
  sub->add_option("--partition", o.resources.partition, "Partition (default: the cluster's)");
  sub->add_option("--job-name", o.resources.job_name, "Job name");
  sub->add_option("--sbatch-option", o.resources.extra,
                  "More #SBATCH lines, e.g. --sbatch-option=--account=proj (repeatable)");
  sub->add_flag("--submit", o.submit, "Submit with sbatch and print the job ids");
}

// Submits what write_*_job wrote, printing the job ids; 1 when sbatch fails.
int submit_jobs(const SlurmJobFiles& f, bool with_merge) {
  std::string error;
  std::optional<std::string> array;
  if (!f.array_script.empty()) {
    array = sbatch({}, f.array_script, &error);
    if (!array) {
      std::fprintf(stderr, "curio-lab: %s\n", error.c_str());
      return cli::kRuntimeFailure;
    }
    std::printf("submitted array job %s (indices %s)\n", array->c_str(),
                array_spec(f.array).c_str());
  }
  if (!with_merge) return 0;
  std::vector<std::string> dep;
  if (array) dep = {"--dependency=afterok:" + *array, "--kill-on-invalid-dep=yes"};
  const auto merge = sbatch(dep, f.merge_script, &error);
  if (!merge) {
    std::fprintf(stderr, "curio-lab: %s\n", error.c_str());
    return cli::kRuntimeFailure;
  }
  std::printf("submitted merge job %s%s\n", merge->c_str(),
              array ? (" (after array job " + *array + " succeeds)").c_str() : "");
  return 0;
}

std::string this_binary() {
  std::error_code ec;
  const auto p = std::filesystem::canonical("/proc/self/exe", ec);
  return ec ? "curio-lab" : p.string();
}

// The trainer built beside this curio-lab, if there is one.
std::string sibling_trainer() {
  const auto sibling =
      std::filesystem::path(this_binary()).parent_path().parent_path() / "train" / "curio-train";
  return std::filesystem::exists(sibling) ? sibling.string() : "";
}

}  // namespace

CLI::App* add_slurm_command(CLI::App& app, CampaignOptions& campaign, SlurmCommandOptions& o) {
  auto* slurm = app.add_subcommand(
      "slurm",
      "Write (and --submit) a Slurm job array for a campaign: one task per chunk of "
      "runs, then a merge job; resubmitting runs only what is missing (docs/cluster.md)");
  add_campaign_options(slurm, campaign);
  add_slurm_options(slurm, o);
  o.resources.cpus = 1;
  slurm->add_option("--chunk", o.chunk, "Runs per array task, at most")->capture_default_str();
  slurm->add_option("--bin", o.binary, "curio-lab as the nodes see it (default: this one)");
  return slurm;
}

CLI::App* add_slurm_train_command(CLI::App& app, SlurmCommandOptions& o) {
  auto* train =
      app.add_subcommand("slurm-train",
                         "Write (and --submit) a Slurm job array training one seed per task with a "
                         "resumable script (SCRIPT OUT/seed-S S); finished seeds are left out");
  add_slurm_options(train, o);
  train->add_option("--script", o.train_script, "e.g. host_tools/train/train_beta_vae.sh")
      ->required();
  train->add_option("--seeds", o.train_seeds, "Seeds: 2,3,4 or 2-4")->required();
  train->add_option("--trainer", o.trainer,
                    "curio-train for the script (CURIO_TRAIN; default: the one built beside "
                    "this curio-lab)");
  train->add_option("--done", o.done_file, "File under OUT/seed-S that marks S finished")
      ->capture_default_str();
  return train;
}

int slurm_command(const CLI::App& command, const CampaignOptions& campaign,
                  const SlurmCommandOptions& s) {
  CampaignConfig c;
  std::string problem;
  if (!build_campaign(campaign, &c, &problem)) return cli::usage_error(command, problem);
  if (s.chunk < 1) return cli::usage_error(command, "--chunk must be >= 1");
  if (s.resources.cpus < 1) return cli::usage_error(command, "--cpus must be >= 1");
  CampaignJobRequest q;
  q.config = c;
  q.run_options = campaign_run_options(c);
  q.out_dir = std::filesystem::absolute(s.out).lexically_normal().string();
  q.binary = s.binary.empty() ? this_binary() : s.binary;
  q.chunk = s.chunk;
  q.resources = s.resources;
  if (q.resources.job_name.empty()) q.resources.job_name = "curio-lab";
  SlurmJobFiles f;
  std::string error;
  if (!write_campaign_job(q, &f, &error)) return cli::usage_error(command, error);
  std::printf(
      "curio-lab slurm: %zu runs in %d tasks; %zu to run (%s), time %s per task (%s)\n"
      "  scripts in %s/ (submit.sh submits them); results will be in %s/\n",
      expand_runs(c).size(), f.tasks, f.array.size(),
      f.array.empty() ? "none: every task is complete" : array_spec(f.array).c_str(),
      f.time.c_str(), f.time_basis.c_str(), f.dir.c_str(), q.out_dir.c_str());
  return s.submit ? submit_jobs(f, true) : 0;
}

int slurm_train_command(const CLI::App& command, SlurmCommandOptions s) {
  if (command.get_option("--cpus")->count() == 0) s.resources.cpus = 2;
  if (s.resources.cpus < 1) return cli::usage_error(command, "--cpus must be >= 1");
  TrainJobRequest q;
  std::string error;
  const auto parsed = parse_seeds(s.train_seeds, &error);
  if (!parsed) return cli::usage_error(command, "--seeds: " + error);
  // Slurm array indices: at most its MaxArraySize limit's ceiling (4,000,001 tasks).
  constexpr uint64_t kMaxArrayIndex = 4000000;
  for (const uint64_t seed : *parsed) {
    if (seed > kMaxArrayIndex)
      return cli::usage_error(command, "--seeds: seed " + std::to_string(seed) +
                                           " is beyond Slurm's largest array index (" +
                                           std::to_string(kMaxArrayIndex) + ")");
    q.seeds.push_back(static_cast<int>(seed));
  }
  std::error_code ec;
  q.script = std::filesystem::canonical(s.train_script, ec).string();
  if (ec) return cli::usage_error(command, "--script: no training script " + s.train_script);
  q.out_dir = std::filesystem::absolute(s.out).lexically_normal().string();
  q.trainer = s.trainer.empty() ? sibling_trainer() : s.trainer;
  q.done_file = s.done_file;
  q.resources = s.resources;
  if (q.resources.job_name.empty()) q.resources.job_name = "curio-train";
  if (q.resources.time.empty()) q.resources.time = "2:00:00";
  SlurmJobFiles f;
  if (!write_train_job(q, &f, &error)) return cli::usage_error(command, error);
  std::printf(
      "curio-lab slurm-train: %d seeds; %zu to train (%s), time %s each\n"
      "  scripts in %s/ (submit.sh submits them); seed S trains in %s/seed-S/\n",
      f.tasks, f.array.size(),
      f.array.empty() ? "none: every seed is finished" : array_spec(f.array).c_str(),
      q.resources.time.c_str(), f.dir.c_str(), q.out_dir.c_str());
  return s.submit ? submit_jobs(f, false) : 0;
}

}  // namespace curio::lab
