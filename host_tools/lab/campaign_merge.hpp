// The merge of a campaign's task folders (campaign_task.hpp) back into the results of the
// whole campaign, in expand_runs' order: the same RunResults a single local run_campaign
// gives, for the report to write the same files (wall times aside).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "host_tools/experiment/campaign_config.hpp"

namespace curio::lab {

struct MergedCampaign {
  CampaignConfig config;  // from the manifests (out_dir, threads, quiet: defaults)
  int tasks = 0;
  std::vector<std::string> task_dirs;  // the task folders found, by task index
  std::vector<RunResult> results;      // every recorded run, failed ones included, campaign order
  std::vector<std::string> missing;    // "run 17 MGE-EFR_sigma0.05_seed2 (task 2): why"
  std::vector<std::string> failed;     // "run 17 MGE-EFR_sigma0.05_seed2 (task 2): the error"
  double run_seconds = 0.0;            // the recorded runs' own wall times, summed
};

// Each of `dirs` is a task folder (it has manifest.json) or a folder of task folders.
// nullopt with *error when there is no task folder, or they are not one campaign split one
// way (the error names the difference), or two folders claim the same task.
std::optional<MergedCampaign> merge_tasks(const std::vector<std::string>& dirs, std::string* error);

}  // namespace curio::lab
