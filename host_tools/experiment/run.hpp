// One exploration run: an algorithm, a seed and a σ, in-process against a simulated world.
// Records what the metric, the tables and the plots need.
#pragma once
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "firmware/explore/explorer_config.hpp"
#include "firmware/journal/journal_format.hpp"
#include "host_tools/experiment/algorithms.hpp"
#include "host_tools/experiment/controllability.hpp"
#include "sim/world.hpp"

namespace curio {
class Explorer;
}

namespace curio::lab {

// A run is the firmware Explorer's own configuration plus what only the lab has: the
// algorithm by its paper name, the simulated world and how often interest is recorded.
struct RunSpec {
  AlgorithmSpec algorithm;
  // σ, D (competence_cap), W, ε, bootstrap, episodes (after the bootstrap), seed, tie rule,
  // competence measure, re-query. Its algorithm, outcome dim, modules and goal kind are
  // ignored: make_explorer_config sets them from `algorithm`.
  ExplorerConfig explorer;
  sim::Physics physics = sim::Physics::kKinematic;
  sim::WorldParams world;
  int interest_every = 50;         // record every module's interest every this many episodes
};

struct RunResult {
  RunSpec spec;
  std::vector<int> checkpoints;       // episode counts N (curve_checkpoints)
  std::vector<double> ratio;          // exploration ratio after the first N episodes
  std::vector<int> grasps;            // grasped episodes among the first N
  std::vector<std::array<float, 2>> final_ball;  // every episode's final ball position
  std::vector<std::array<float, 2>> final_distractor;  // and distractor (scene_log.hpp)
  std::vector<int> interest_episodes;            // episode counts of the interest samples
  std::vector<std::vector<float>> interest;      // [sample][module] |cp|
  std::vector<ProgressSample> exploits;          // every exploit's module and progress p
  std::vector<int> module_choices;               // how often each module was chosen
  std::vector<std::string> module_names;         // "ball", "z3+z7", ...
  std::vector<std::vector<int>> module_latents;  // learned goal spaces: latents of each module
  std::vector<ModuleVerdict> verdicts;           // controllable-feature discovery (MGE/RGE)
  double seconds = 0.0;                // wall time
  double cpu_seconds = 0.0;            // this run's thread CPU time (robust to a busy machine)
  std::string error;                  // non-empty: the run failed
};

// The world seed is derived from the run seed so that runs with the same seed see the same
// distractor walk whatever the algorithm.
uint64_t world_seed(uint64_t run_seed);

// The Explorer config of a run: spec.explorer with the modules of spec.algorithm (exposed for
// validation and tests).
Status make_explorer_config(const RunSpec& spec, ExplorerConfig* config);

// The controllable modules' names ("ball", or latents "z3,z7"), "none" if no module is.
std::string verdict_text(const RunResult& r);

// Ground truth for that verdict, in the same spelling: "ball" (engineered features) or the
// ball's latents from the trainer's factor report ("z0,z2"); "" when unknown (RPE, no report).
std::string expected_verdict(const RunResult& r);

// What ends a run early: a stop request (Ctrl-C) seen before an episode.
inline constexpr const char* kStopped = "stopped before its last episode";

// Optional hooks of one run (curio-lab's per-run journal and Ctrl-C: local_campaign.hpp).
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
