#include "host_tools/lab/campaign_task.hpp"


#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <mutex>

#include "host_tools/common/atomic_file.hpp"
#include "host_tools/experiment/campaign_json.hpp"
#include "host_tools/experiment/report.hpp"
#include "host_tools/lab/campaign_runner.hpp"
#include "host_tools/lab/run_record.hpp"

namespace curio::lab {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {
std::string describe(const json& m) {
  return "task " + m.value("task", json()).dump() + " of " + m.value("tasks", json()).dump();
}
}  // namespace

int tasks_for_chunk(size_t runs_in_campaign, int chunk) {
  const size_t k = static_cast<size_t>(std::max(chunk, 1));
  return static_cast<int>(std::max<size_t>((runs_in_campaign + k - 1) / k, 1));
}

std::string record_path(const std::string& dir, size_t index) {
  return (fs::path(dir) / "records" / ("run-" + std::to_string(index) + ".cbor")).string();
}

std::vector<size_t> runs_to_do(const CampaignConfig& config, const std::string& dir, int task,
                               int tasks, std::vector<std::string>* unusable) {
  const auto specs = expand_runs(config);
  const auto mine = task_runs(specs.size(), task, tasks);
  std::string error;
  const auto m = read_task_manifest(dir, &error);
  if (!m || m->task != task || m->tasks != tasks || m->campaign != campaign_to_json(config))
    return mine;
  std::vector<size_t> todo;
  for (size_t i : mine) {
    const std::string path = record_path(dir, i);
    const auto r = read_run_record(path, i, specs[i], &error);
    if (!r && unusable != nullptr && fs::exists(path))
      unusable->push_back("run " + std::to_string(i) + " (" + run_stem(specs[i]) + "): " + error +
                          "; it runs again");
    if (!r || !r->error.empty()) todo.push_back(i);
  }
  return todo;
}

bool run_task(const CampaignConfig& config, int task, int tasks, TaskOutcome* outcome,
              std::string* error, const std::atomic<bool>* stop) {
  const std::string dir = config.out_dir;
  const json manifest = manifest_json(config, task, tasks);
  if (fs::exists(manifest_path(dir))) {
    std::ifstream f(manifest_path(dir));
    const json old = json::parse(f, nullptr, false);
    if (old.is_discarded() || old.value("campaign", json()) != manifest["campaign"] ||
        old.value("task", -1) != task || old.value("tasks", -1) != tasks) {
      std::string why = "the folder holds " + describe(old);
      for (const auto& d :
           campaign_differences(old.value("campaign", json::object()), manifest["campaign"]))
        why += "; " + d;
      *error = dir + " is not task " + std::to_string(task) + " of " + std::to_string(tasks) +
               " of this campaign (" + why + "): use another --out";
      return false;
    }
  }
  std::error_code ec;
  fs::create_directories(fs::path(dir) / "records", ec);
  if (ec) {
    *error = "cannot create " + (fs::path(dir) / "records").string() + ": " + ec.message();
    return false;
  }
  if (!host::write_file_atomically(manifest_path(dir), manifest.dump(2) + "\n", error))
    return false;
  const auto specs = expand_runs(config);
  const auto todo = runs_to_do(config, dir, task, tasks, &outcome->redone);
  outcome->runs = task_runs(specs.size(), task, tasks).size();
  outcome->skipped = outcome->runs - todo.size();
  std::vector<RunSpec> some;
  for (size_t i : todo) some.push_back(specs[i]);
  std::mutex m;
  std::string write_error;
  std::atomic<size_t> failed{0}, stopped{0};
  if (some.empty()) return true;
  run_some(
      config, some, &outcome->wall_seconds,
      [&](size_t k, const RunResult& r) {
        if (stopped_early(r)) {
          ++stopped;
          return;
        }
        if (!r.error.empty()) ++failed;
        std::string e;
        if (!write_run_record(record_path(dir, todo[k]), todo[k], r, &e)) {
          std::lock_guard lock(m);
          write_error = e;
        }
      },
      stop);
  outcome->failed = failed;
  outcome->stopped = stopped;
  if (!write_error.empty()) {
    *error = write_error;
    return false;
  }
  return true;
}

}  // namespace curio::lab
