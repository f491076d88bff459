// The episodes of a run over the bus, one after another until the explorer is done or an
// episode fails: each episode the Controller runs (with its retries and recoveries) is recorded
// as curio-lab records it, the bus history is rewritten when the fault counters change, and a
// progress line goes out every progress_every_s seconds.
#pragma once
#include "firmware/app/controller.hpp"
#include "host_tools/controller/bus_history.hpp"
#include "host_tools/controller/bus_run.hpp"
#include "host_tools/experiment/run_recorder.hpp"

namespace curio::app::host {

// Runs the remaining episodes. Sets out->seconds (and out->run.seconds) to their wall time, and
// out->run.error when an episode fails (episode_failure_text).
void run_episodes(Controller& controller, const Explorer& explorer, lab::RunRecorder& recorder,
                  BusHistoryFile& history, const BusRunOptions& options, BusRunResult* out);

}  // namespace curio::app::host
