// One online exploration run: random bootstrap → train the β-VAE on the final images
// the agent has observed → goal modules from the latents' KL → explore in that goal space
// with the firmware Explorer → every retrain_every episodes retrain (warm start), re-encode
// every archived outcome with the new encoder, rebuild the modules → continue.
//
// Rebuilding the Explorer: Explorer::rebase swaps the modules and rewrites the archive's
// outcomes in place, keeping the θ recipes (what the arm executed), the PRNG streams and the
// episode count; interest carries over by latent (goal_space.hpp). A replay of the run into
// a fresh Explorer with re-encoded outcomes would be wrong: its nearest-neighbour queries, and
// so its θ, would differ from the θ that produced the stored scenes.
//
// Memory: the agent's images are not stored; every episode keeps its final scene (ball and
// distractor position, 16 bytes) and a training re-renders all of them (12 KiB an image while
// it trains: 10,400 images = 122 MiB, freed after the re-encoding).
//
// Novelty steps (options.novelty_fraction > 0): the surprise of every archived episode (BCE of
// its final image decoding μ under the current model) is kept beside the archive, rewritten
// at each retrain; a step chosen by Prng(seed, kNoveltyStream) explores around one of the
// worst-reconstructed novelty_top of the archive (Explorer::explore_around).
//
// Checkpoint and resume: after training r the run writes models/round_<r>.pt (weights and
// Adam state), scenes.csv and state.json (rounds done, a hash of the scenes seen at each).
// The exploration itself is cheap and deterministic given the models, so --resume replays
// it from episode 0, loading round r's model where it would train it (and checking that the
// scenes seen so far hash as recorded), then trains on from the last round done: a resumed run
// gives the same results, bit for bit, as an uninterrupted one (one thread).
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "host_tools/experiment/controllability.hpp"
#include "host_tools/online/goal_space.hpp"
#include "host_tools/online/online_options.hpp"
#include "host_tools/online/online_training.hpp"

namespace curio::online {

// What one (re)training found. The factor report is evaluation only (SPEC §3's uniform
// held-out scenes against their true positions); nothing in it reaches the explorer.
struct RetrainRecord {
  int round = 0;
  int episode = 0;                       // archive size when it ran
  bool loaded = false;                   // resumed: the model came from its checkpoint
  TrainingStats training;
  std::array<double, 10> kl{};           // on the agent's images (what orders the modules)
  std::array<uint8_t, 10> kl_order{};
  // Mean and standard deviation of each latent's μ over the agent's images: where the outcomes
  // lie against the N(0, 1) the goals are drawn from.
  std::array<double, 10> mu_mean{};
  std::array<double, 10> mu_std{};
  std::vector<std::vector<int>> modules;
  std::vector<float> carried_cp;         // the new modules' starting cp
  nlohmann::json factor_report;
  std::vector<std::vector<double>> corr;  // [latent][factor] Pearson of μ, held-out
  std::vector<int> ball_latents;         // active, best factor ball x/y, |corr| ≥ .5
  std::vector<int> distractor_latents;   // the same for the distractor
  // The same report on the agent's own images so far against their true scenes (evaluation
  // only). Early models never saw the ball away from its rest spot, so SPEC §3's uniform
  // scenes are far outside their data; this says what the code holds on the data it had.
  nlohmann::json own_factor_report;
  std::vector<int> own_ball_latents;
  std::vector<int> own_distractor_latents;
  // The segment that ended here (the previous goal space's modules): verdict per module.
  std::vector<std::vector<int>> segment_modules;
  std::vector<lab::ModuleVerdict> segment_verdicts;
  std::vector<int> segment_controllable;  // latents of its controllable modules
  uint32_t scenes_hash = 0;
};

struct OnlineResult {
  std::vector<Scene> scenes;
  std::vector<int> checkpoints;          // lab::curve_checkpoints
  std::vector<double> ratio;
  int grasps = 0;
  std::vector<int> interest_episodes;    // samples of every module slot's interest
  std::vector<std::vector<float>> interest;
  std::vector<lab::ProgressSample> exploits;
  std::vector<RetrainRecord> retrains;
  // Final verdict: the segment since the last retrain.
  std::vector<std::vector<int>> final_modules;
  std::vector<lab::ModuleVerdict> final_verdicts;
  std::vector<int> verdict_latents;
  std::vector<int> ball_latents;         // of the final model
  bool verdict_matches = false;          // verdict_latents == ball_latents, both non-empty
  // The same against the final model's ball latents on the agent's own images (evaluation
  // only): SPEC §3's uniform scenes put the ball where the agent never took it.
  std::vector<int> own_ball_latents;
  bool verdict_matches_own = false;
  int rebases = 0;
  // Novelty steps (options.novelty_fraction): steps run, and per episode whether it belonged
  // to one (1) or not (0), for the evaluation-only ball-moved shares in summary.json.
  int novelty_steps = 0;
  std::vector<uint8_t> novelty_episode;
  uint32_t archive_checksum = 0;         // Fnv1a over the final archive (θ and outcomes)
  double seconds = 0.0;                  // wall time of this process's run (a pause counts)
  double cpu_seconds = 0.0;              // CPU time of this process's run, all threads
  bool stopped = false;                  // stop_after_retrain reached
};

using ProgressFn = std::function<void(const std::string&)>;

// Runs (or, with rounds_done > 0, resumes) the run described by `o` in o.out_dir.
// Throws std::runtime_error on I/O failures, a failed explorer call or a replay that does not
// match the checkpoint.
OnlineResult run_online(const OnlineOptions& o, int rounds_done, const ProgressFn& progress);

// "z1,z4", or "none".
std::string latents_text(const std::vector<int>& latents);

}  // namespace curio::online
