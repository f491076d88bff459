// The episodes of a run over the bus, one after another until the explorer is done or an
// episode fails: each episode the Controller runs (with its retries and recoveries) is recorded
// as curio-lab records it, the bus history is rewritten when the fault counters change, and a
// progress line goes out every progress_every_s seconds.
#pragma once
#include "firmware/app/controller.hpp"
#include "host_tools/controller/bus_history.hpp"
#include "host_tools/controller/bus_run_types.hpp"
#include "host_tools/experiment/run_recorder.hpp"
#include "host_tools/journal/run_journal.hpp"

namespace curio::app::host {

// Runs the remaining episodes. Sets out->seconds (and out->run.seconds) to their wall time, and
// out->run.error when an episode fails (episode_failure_text), or when `journal` (null: none)
// cannot take an episode: then the error names the file and the cause (a full disk), and the
// run stops at once, its journal whole up to the episode before.
void run_episodes(Controller& controller, const Explorer& explorer, lab::RunRecorder& recorder,
                  BusHistoryFile& history, const journal::host::RunJournal* journal,
                  const BusRunOptions& options, BusRunResult* out);

}  // namespace curio::app::host
