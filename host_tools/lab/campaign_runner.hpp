// A campaign run in-process: its runs (host_tools/experiment/simulated_run.hpp) on all
// cores, progress lines on stderr. `curio-lab run` runs a whole campaign, a task its share.
#pragma once
#include <atomic>
#include <cstddef>
#include <functional>
#include <vector>

#include "host_tools/experiment/campaign_config.hpp"
#include "host_tools/experiment/simulated_run.hpp"

namespace curio::lab {

// Runs them on `config.threads` threads, printing progress lines to stderr.
std::vector<RunResult> run_campaign(const CampaignConfig& config, double* wall_seconds);

// The same for some of them (a task's share): results in the order of `runs`; `on_done`
// (optional) sees each result, with its position in `runs`, on the worker thread that ran it,
// and may shrink it (a caller that streams results to disk drops what it has written). Once
// `*stop` (optional) is set, no further run starts, those running end before their next
// episode (error kStopped, simulated_run.hpp), and the runs never started come back with error
// kNotStarted. `hooks_for` (optional) gives the hooks of the run at a position in `runs`
// (its stop is `stop`).
inline constexpr const char* kNotStarted = "not started (stopped)";
std::vector<RunResult> run_some(const CampaignConfig& config, const std::vector<RunSpec>& runs,
                                double* wall_seconds,
                                const std::function<void(size_t, RunResult&)>& on_done = {},
                                const std::atomic<bool>* stop = nullptr,
                                const std::function<RunHooks(size_t)>& hooks_for = {});

// Whether a result is of a run that a stop request cut short or never started.
inline bool stopped_early(const RunResult& r) {
  return r.error == kStopped || r.error == kNotStarted;
}

}  // namespace curio::lab
