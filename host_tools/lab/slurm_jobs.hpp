// Slurm job arrays for curio-lab campaigns and curio-train seeds: the sbatch scripts, what a
// resubmission still has to run, and the submission itself (sbatch --parsable).
//
// A campaign job in OUT (absolute; a shared filesystem is assumed):
//   OUT/slurm/campaign.json   the campaign and its split; a later call must match it
//   OUT/slurm/array.sbatch    one array task per chunk: `curio-lab run ... --task I --tasks N
//                             --out OUT/tasks/task-I` (campaign_task.hpp)
//   OUT/slurm/merge.sbatch    `curio-lab merge OUT/tasks --out OUT`, after the array succeeds
//   OUT/slurm/submit.sh       the same submission by hand
//   OUT/slurm/logs/           task-<I>.out, merge.out
// Only tasks with runs still to do go into the array (a task skips its recorded runs too).
#pragma once
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "host_tools/experiment/campaign_config.hpp"

namespace curio::lab {

struct SlurmResources {
  int cpus = 1;           // --cpus-per-task (a task runs that many runs at once)
  std::string time;       // --time; empty: estimated (campaigns) or a default
  std::string partition;  // empty: the cluster's default
  std::string job_name;
  std::vector<std::string> extra;  // more #SBATCH lines, e.g. --account=proj
};

struct CampaignJobRequest {
  CampaignConfig config;
  std::vector<std::string> run_options;  // the campaign as `curio-lab run` options
  std::string out_dir;
  std::string binary;  // curio-lab as the nodes see it
  int chunk = 10;      // runs per array task, at most
  SlurmResources resources;
};

struct SlurmJobFiles {
  std::string dir;           // OUT/slurm
  std::string array_script;  // empty when nothing is left to run
  std::string merge_script;  // empty for training
  std::string submit_script;
  std::vector<int> array;  // the array indices submitted (tasks, or seeds)
  int tasks = 0;           // campaign: N; training: seeds
  std::string time;        // what was requested per array task
  std::string time_basis;  // how it was chosen
};

// The campaign as `curio-lab run` options (values that parse back to the same numbers).
std::vector<std::string> campaign_run_options(const CampaignConfig& config);

// Array indices in sbatch's syntax: {0,1,2,5,7,8} → "0-2,5,7-8".
std::string array_spec(const std::vector<int>& indices);

// Seconds as a Slurm time limit, rounded up to whole minutes: 3725 → "1:03:00".
std::string slurm_time(double seconds);

// CPU seconds per episode (bootstrap included) of each of the campaign's algorithms, in
// campaign order: one run of each (first seed and σ) with `episodes` exploration episodes.
std::vector<std::pair<std::string, double>> cpu_seconds_per_episode(const CampaignConfig& config,
                                                                    int episodes);

// The wall time one array task of `runs_per_task` runs on `cpus` cores should need: a short
// calibration run of each algorithm (this machine's rate, per CPU-second), scaled to the
// campaign's episodes, × 3 for slower or busier nodes, + 5 minutes. *basis says so.
double estimate_task_seconds(const CampaignConfig& config, int runs_per_task, int cpus,
                             std::string* basis);

// Writes OUT/slurm/* for the runs still to do; false with *error when OUT holds another
// campaign or split (the error names the difference) or a file cannot be written.
bool write_campaign_job(const CampaignJobRequest& request, SlurmJobFiles* files,
                        std::string* error);

struct TrainJobRequest {
  std::string script;      // the resumable training script: SCRIPT OUT_DIR SEED
  std::vector<int> seeds;  // array indices = seeds (Slurm's MaxArraySize bounds them)
  std::string out_dir;     // seed S trains in OUT/seed-S
  std::string trainer;     // CURIO_TRAIN for the script; empty: the script's default
  std::string done_file;   // relative to OUT/seed-S: present once that seed is finished
  SlurmResources resources;
};

// Writes OUT/slurm/train.sbatch and submit.sh for the seeds not finished yet.
bool write_train_job(const TrainJobRequest& request, SlurmJobFiles* files, std::string* error);

// `sbatch --parsable ARGS... SCRIPT`: the job id, or nullopt with *error (sbatch's message).
std::optional<std::string> sbatch(const std::vector<std::string>& args, const std::string& script,
                                  std::string* error);

// Single-quoted for sh.
std::string shell_quote(const std::string& s);

}  // namespace curio::lab
