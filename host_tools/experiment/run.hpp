// One exploration run: its specification (an algorithm, a seed, a σ, the world) and its
// result (what the metric, the tables and the plots need), whoever runs it: in-process against
// the simulated world (simulated_run.hpp) or over the CAN bus (curio-controller).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "firmware/explore/explorer_config.hpp"
#include "host_tools/experiment/algorithms.hpp"
#include "host_tools/experiment/controllability.hpp"
#include "sim/world.hpp"

namespace curio::lab {

struct Representation;

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
  // and distractor (the scene logs: host_tools/lab/scene_log.hpp)
  std::vector<std::array<float, 2>> final_distractor;
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

// The learned representation of a run (representations.hpp), or nullptr: engineered features,
// RPE, or weights missing from this build.
const Representation* representation_of(const RunSpec& spec);

// The Explorer config of a run: spec.explorer with the modules of spec.algorithm (exposed for
// validation and tests).
Status make_explorer_config(const RunSpec& spec, ExplorerConfig* config);

// The controllable modules' names ("ball", or latents "z3,z7"), "none" if no module is.
std::string verdict_text(const RunResult& r);

// Ground truth for that verdict, in the same spelling: "ball" (engineered features) or the
// ball's latents from the trainer's factor report ("z0,z2"); "" when unknown (RPE, no report).
std::string expected_verdict(const RunResult& r);

}  // namespace curio::lab
