// The journal of a run over the bus (host_tools/journal/run_journal.hpp, in --out): opened and
// checked before the arm moves, so that a resume of another run's journal, or of a corrupt one,
// is refused with nothing on the bus changed; then, once the arm is up and its physics known,
// started afresh or replayed into the explorer and the recorder, after which the controller
// appends every episode to it. Also curio-controller's guard on a used --out: it is resumed or
// replaced, never silently mixed.
#pragma once
#include <memory>
#include <string>

#include "firmware/app/controller.hpp"
#include "host_tools/controller/bus_run_types.hpp"
#include "host_tools/experiment/run_recorder.hpp"
#include "host_tools/journal/run_journal.hpp"

namespace curio::app::host {

struct BusJournal {
  std::unique_ptr<journal::host::RunJournal> file;  // null: the run keeps no journal
  bool resume = false;  // replay the journaled episodes (options.resume and something to replay)
};

// Opens options.journal_path (none when empty) and decides whether the run resumes. false with
// out->run.error: the file cannot be opened, or a resume is refused (another run's journal,
// corruption before its tail).
bool open_bus_journal(const BusRunOptions& options, const ExplorerConfig& config,
                      BusJournal* journal, BusRunResult* out);

// After bring_up_arm: a new journal (identity of the run on this arm's physics), or the
// journaled episodes replayed into `explorer` and `recorder` (out->resumed_episodes,
// out->journal_notice); then the controller journals every episode. No journal: nothing to do.
// false with out->run.error.
bool start_bus_journal(BusJournal& journal, const BusRunOptions& options,
                       const ExplorerConfig& config, Explorer& explorer, lab::RunRecorder& recorder,
                       Controller& controller, BusRunResult* out);

enum class OutFolder { kReady, kHoldsJournal, kCannotCreate };

// curio-controller's --out before a journaled run: created if absent; kHoldsJournal (with
// *message saying what it holds and what to do) when it holds a journal and the run neither
// resumes nor replaces it. A file that holds no journal (a run that stopped before its first
// episode) has nothing to lose and does not block a new run.
OutFolder prepare_out_folder(const std::string& out_dir, const std::string& journal_path,
                             bool resume, bool replace, std::string* message);

}  // namespace curio::app::host
