#include "host_tools/lab/campaign_merge.hpp"

#include <algorithm>
#include <filesystem>

#include "host_tools/experiment/campaign_json.hpp"
#include "host_tools/experiment/report.hpp"
#include "host_tools/lab/campaign_task.hpp"
#include "host_tools/lab/run_record.hpp"

namespace curio::lab {
namespace fs = std::filesystem;

std::optional<MergedCampaign> merge_tasks(const std::vector<std::string>& dirs,
                                          std::string* error) {
  std::vector<std::string> found;
  for (const auto& d : dirs) {
    if (fs::exists(manifest_path(d))) {
      found.push_back(d);
      continue;
    }
    std::vector<std::string> inside;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(d, ec))
      if (e.is_directory() && fs::exists(manifest_path(e.path().string())))
        inside.push_back(e.path().string());
    if (ec || inside.empty()) {
      *error = d + " is neither a task folder (no manifest.json) nor a folder of task folders";
      return std::nullopt;
    }
    std::sort(inside.begin(), inside.end());
    found.insert(found.end(), inside.begin(), inside.end());
  }

  std::vector<TaskManifest> manifests;
  for (const auto& d : found) {
    auto m = read_task_manifest(d, error);
    if (!m) return std::nullopt;
    manifests.push_back(std::move(*m));
  }
  const TaskManifest& first = manifests.front();
  for (size_t k = 1; k < manifests.size(); ++k) {
    const auto diff = campaign_differences(first.campaign, manifests[k].campaign);
    if (!diff.empty()) {
      std::string why;
      for (const auto& line : diff) why += "\n  " + line;
      *error = found[k] + " belongs to another campaign than " + found[0] + " (" + found[0] +
               " vs " + found[k] + "):" + why;
      return std::nullopt;
    }
    if (manifests[k].tasks != first.tasks) {
      *error = found[k] + " is one of " + std::to_string(manifests[k].tasks) + " tasks, " +
               found[0] + " one of " + std::to_string(first.tasks) +
               ": the campaign was split two ways";
      return std::nullopt;
    }
  }
  MergedCampaign out;
  auto config = campaign_from_json(first.campaign, error);
  if (!config) return std::nullopt;
  out.config = *config;
  out.tasks = first.tasks;
  out.task_dirs.assign(static_cast<size_t>(first.tasks), "");
  for (size_t k = 0; k < manifests.size(); ++k) {
    std::string& slot = out.task_dirs[static_cast<size_t>(manifests[k].task)];
    if (!slot.empty()) {
      *error =
          "task " + std::to_string(manifests[k].task) + " is both " + slot + " and " + found[k];
      return std::nullopt;
    }
    slot = found[k];
  }
  const auto specs = expand_runs(out.config);
  if (specs.size() != first.runs_in_campaign) {
    *error = "the manifests count " + std::to_string(first.runs_in_campaign) +
             " runs, this build expands the campaign to " + std::to_string(specs.size());
    return std::nullopt;
  }
  for (size_t i = 0; i < specs.size(); ++i) {
    const int task = static_cast<int>(i % static_cast<size_t>(out.tasks));
    const std::string& dir = out.task_dirs[static_cast<size_t>(task)];
    const std::string what = "run " + std::to_string(i) + " " + run_stem(specs[i]) + " (task " +
                             std::to_string(task) + ")";
    if (dir.empty()) {
      out.missing.push_back(what + ": no folder of task " + std::to_string(task) + " given");
      continue;
    }
    std::string why;
    auto r = read_run_record(record_path(dir, i), i, specs[i], &why);
    if (!r) {
      out.missing.push_back(what + ": " + why);
      continue;
    }
    if (!r->error.empty()) out.failed.push_back(what + ": " + r->error);
    out.run_seconds += r->seconds;
    out.results.push_back(std::move(*r));
  }
  return out;
}

}  // namespace curio::lab
