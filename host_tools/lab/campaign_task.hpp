// A campaign split into tasks (a Slurm job array, several machines): which runs each task
// holds, and the task folder it leaves for the merge:
//   manifest.json            the campaign, task I of N and its runs (task_manifest.hpp)
//   records/run-<index>.cbor one record per finished run (run_record.hpp)
// Task I of N holds the runs i of expand_runs' fixed order with i mod N = I: every run in
// exactly one task, each task a mix of algorithms (they differ in cost), and a task's share
// depends only on the campaign's size and N.
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "host_tools/experiment/campaign_config.hpp"
#include "host_tools/lab/task_manifest.hpp"

namespace curio::lab {

// How many tasks of at most `chunk` runs the campaign needs: ceil(runs / chunk), at least 1.
int tasks_for_chunk(size_t runs_in_campaign, int chunk);

std::string record_path(const std::string& dir, size_t index);

// The runs of task `task` that `dir` has no successful record of (all of them when `dir`
// does not exist). A failed run counts as not done: resubmitting runs it again. A record that
// is there but cannot be used (damaged: its CRC does not match; unreadable; another run's)
// runs again too, and `unusable` (optional) gets one line on each, to be reported.
std::vector<size_t> runs_to_do(const CampaignConfig& config, const std::string& dir, int task,
                               int tasks, std::vector<std::string>* unusable = nullptr);

struct TaskOutcome {
  size_t runs = 0;     // in the task
  size_t skipped = 0;  // already recorded by an earlier attempt
  size_t failed = 0;   // ran now and failed
  size_t stopped = 0;  // cut short or never started by a stop request (not recorded)
  double wall_seconds = 0.0;
  std::vector<std::string> redone;  // records found unusable (runs_to_do): they ran again
};

// Runs task `task` of `tasks` into config.out_dir: writes the manifest (or checks that the
// folder's manifest is this very task's), skips the runs already recorded, and writes each
// run's record as soon as it finishes (a task killed mid-way keeps its finished runs).
// false with *error when the folder holds another campaign or task, or a write fails. Once
// `*stop` (optional) is set, runs in flight end unrecorded and no further run starts.
bool run_task(const CampaignConfig& config, int task, int tasks, TaskOutcome* outcome,
              std::string* error, const std::atomic<bool>* stop = nullptr);

}  // namespace curio::lab
