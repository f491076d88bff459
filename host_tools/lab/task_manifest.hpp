// A campaign task's manifest.json: which campaign the task folder belongs to and which of its
// runs the task holds. Written when a task starts, read back by a resumed task, `curio-lab
// merge` and a local campaign's --out check; parsed from text so that damage is caught here
// (tests/fuzz/fuzz_host_files.cpp feeds it arbitrary and damaged files).
//   {"format": "curio-lab task", "version": 1, "campaign": {...campaign_to_json...},
//    "runs_in_campaign": R, "task": I, "tasks": N, "runs": [{"index": i, "name": ...}, ...]}
// Task I of N holds the runs i of expand_runs' fixed order with i mod N = I, ascending.
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "host_tools/experiment/campaign_config.hpp"

namespace curio::lab {

// The run indices of task `task` of `tasks`, ascending (empty unless 0 ≤ task < tasks).
std::vector<size_t> task_runs(size_t runs_in_campaign, int task, int tasks);

struct TaskManifest {
  nlohmann::json campaign;  // campaign_to_json of the campaign
  size_t runs_in_campaign = 0;
  int task = 0;
  int tasks = 0;
  std::vector<size_t> runs;  // task_runs(runs_in_campaign, task, tasks)
};

nlohmann::json manifest_json(const CampaignConfig& config, int task, int tasks);

// The manifest in `text`; nullopt with *error (naming `where`) when it is not JSON, not a
// version-1 task manifest, has a field of the wrong type or range, or its runs are not task
// `task` of `tasks`'s. Never allocates more than the text's own size suggests: a damaged
// runs_in_campaign of 10^18 is refused, not expanded.
std::optional<TaskManifest> parse_task_manifest(std::string_view text, const std::string& where,
                                                std::string* error);
// parse_task_manifest of manifest_path(dir); nullopt with *error when it cannot be read.
std::optional<TaskManifest> read_task_manifest(const std::string& dir, std::string* error);

std::string manifest_path(const std::string& dir);

}  // namespace curio::lab
