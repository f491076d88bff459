// One exploration run in-process against the simulated world (sim::World): the firmware
// Explorer proposes θ, the world rolls the arm out, the controller's own outcome step
// (app::episode_outcome) turns the final scene into the outcome. Bit for bit the archive the
// controller builds over the bus (tests/app/parity_test.cpp). Used by curio-lab's campaigns,
// curio-online's passive baseline and the parity tests.
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "firmware/explore/explorer_config.hpp"
#include "firmware/journal/journal_format.hpp"
#include "host_tools/experiment/run.hpp"

namespace curio {
class Explorer;
}

namespace curio::lab {

// What ends a run early: a stop request (Ctrl-C) seen before an episode.
inline constexpr const char* kStopped = "stopped before its last episode";

// Optional hooks of one run (curio-lab's per-run journal and Ctrl-C:
// host_tools/lab/local_campaign.hpp).
struct RunHooks {
  // Checked before each episode: once set, the run ends with error kStopped.
  const std::atomic<bool>* stop = nullptr;
  // Before the first episode, with the run's Explorer config and its freshly initialised
  // explorer: may replay earlier episodes into it, calling `replayed` after each (which
  // records it); the world is then positioned at the next episode. false with *error: the run
  // fails with that error.
  std::function<bool(const ExplorerConfig&, Explorer&,
                     const std::function<void(const journal::EpisodeEntry&)>& replayed,
                     std::string* error)>
      resume;
  // After each episode is observed (what the journal keeps of it). false with *error: the run
  // fails with that error.
  std::function<bool(const journal::EpisodeEntry&, std::string* error)> on_episode;
};

// Runs to completion. `episodes_done` (optional) is advanced as episodes finish, for progress.
// `on_finish` (optional) sees the explorer at the end (its archive: parity tests).
RunResult run_exploration(const RunSpec& spec, std::atomic<int64_t>* episodes_done = nullptr,
                          const std::function<void(const Explorer&)>& on_finish = {},
                          const RunHooks& hooks = {});

}  // namespace curio::lab
