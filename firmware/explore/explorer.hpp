// The exploration loop of SPEC §2.2 (RPE, RGE, MGE) as a state machine the caller drives,
// so it runs in-process or behind a CAN bus alike.
//
// API (one episode = one propose() then one observe()):
//   static curio::Explorer explorer;          // ~690 KB: static storage, or one allocation
//                                             // at init on the host; never on the stack
//   curio::ExplorerConfig cfg;                // defaults = SPEC (σ 0.05, D 2, W 1000, ε 0.1,
//   curio::set_efr_modules(cfg, curio::Algorithm::kMge);   // 100 bootstrap, 10,000 episodes)
//   cfg.seed = 7;
//   if (explorer.init(cfg) != Status::kOk) ...            // validates; no heap
//   float theta[kThetaDim], outcome[kMaxOutcomeDim];
//   while (!explorer.done()) {
//     explorer.propose(theta);                // θ of episode explorer.episode()
//     ... run the arm with θ, measure cfg.outcome_dim outcome values ...
//     explorer.observe(outcome);              // archive append (+ interest update on exploit)
//   }
// Episodes are numbered 0 .. n_bootstrap + n_episodes − 1 (= archive index). kind() says
// whether the current episode is kBootstrap, kRandom (RPE), kExplore or kExploit; module(),
// goal() give the current step's module and goal; interest(k) every module's interest now.
// propose() before observe() returns the same pending θ again (idempotent, for retries);
// observe() rejects non-finite outcomes (kNonFiniteOutcome) and keeps the episode pending.
//
// Schedule (RGE/MGE): episodes 0 .. n_bootstrap − 1 are random (θ ~ U[-1,1]^49); then steps
// of 5 episodes. At the first episode of a step: choose module k (ε-proportional to interest),
// sample goal g, θ_nn = θ of the archive entry whose module-k outcome is nearest to g.
// Episodes 1–4 of the step (kExplore): θ = clip(θ_nn + N(0, σ² I), −1, 1). Episode 5
// (kExploit): θ = θ_nn re-queried in the archive as it is then (requery_exploit, default),
// and its outcome updates module k's interest. While the archive holds fewer than two
// distinct module-k outcomes, every NN query yields θ ~ U[-1,1]^49 instead (no noise).
// RPE: every episode θ ~ U[-1,1]^49.
//
// Fidelity to the reference code (flowersteam/Curiosity_Driven_Goal_Exploration mge_efr.py /
// mge_fi_armballs.py on explauto NonParametric 'NN', MiscRandomInterest), checked step by step:
//   noise: sigma_explo_ratio = explo_noise_sdev/2, times (m_max − m_min) = 2 → std σ on θ,
//     then bounds_min_max → clip to [-1,1] (same as here); the 4 explore θ come from 4 NN
//     queries on an unchanged archive, i.e. one shared θ_nn; the exploit re-queries after
//     the 4 explore outcomes are stored (requery_exploit);
//   fallback: NonParametric.bootstrapped_s (an outcome differs from the one before it) →
//     θ ~ U without noise for explore and exploit alike (DistinctOutcomes, equivalent);
//   interest: c = competence_dist(g, r, dist_max) (explauto's divides by dist_max instead of
//     clipping: CompetenceMeasure::kScaled; SPEC's clip is kClipped, the default),
//     j = NN of g among the module's past goals,
//     p = c − c(g, r_j), cp += (p − cp)/W, |cp|, start 1e-5, first update p = 0, only the
//     chosen module on its exploit (InterestModel); module choice = explauto prop_choice;
//     goals = rand_bounds over [-1,1]^d. Only 1-NN tie order is implementation-defined
//     there (see nearest_neighbour.hpp); it does not move the results.
//
// Determinism: all randomness comes from four Prng streams, each Prng(seed, stream id):
//   kStreamModuleChoice: 1 uniform01 per step (module choice);
//   kStreamGoal:         d uniform01 (box) or d normal (latent) draws per step (the goal);
//   kStreamRandomTheta:  49 uniform01 per random θ (bootstrap, RPE, too-few-outcomes fallback);
//   kStreamNoise:        49 normal per explore episode that has a θ_nn;
//   kStreamFrontier:     only with frontier_share > 0: 1 uniform01 per step (frontier or not),
//                        and 1 + d per frontier goal (its cell, its point in the cell).
// Same seed and same observed outcomes → the same θ sequence, bit for bit.
//
// Memory: the archive does not store θ. Random θ number r and explore noise number x are
// drawn at their stream positions (ThetaGenerator: PCG32 jump-ahead), and each archived
// episode keeps a 4-byte recipe — (random, r), (explore around entry p, x), or an exploit's
// copy of its source's recipe — from which archive().theta(i, out) regenerates θ with the same
// float operations, bit for bit (archive.hpp; a small θ pool bounds a regeneration to
// kThetaPoolDepth noise vectors). With kArchiveCapacity = 10,400 the Explorer fits an
// STM32H7-class MCU (docs/deploy.md, "Memory budget").
#pragma once
#include <cstdint>

#include "firmware/explore/archive.hpp"
#include "firmware/explore/config.hpp"
#include "firmware/explore/distinct_outcomes.hpp"
#include "firmware/explore/explorer_config.hpp"
#include "firmware/explore/frontier_goals.hpp"
#include "firmware/explore/goal_module.hpp"
#include "firmware/explore/interest_model.hpp"
#include "firmware/explore/prng.hpp"
#include "firmware/explore/status.hpp"
#include "firmware/explore/theta_generator.hpp"

namespace curio {

enum class EpisodeKind : uint8_t {
  kNone,       // not initialised, or done
  kBootstrap,  // random θ before goal exploration starts
  kRandom,     // RPE after the bootstrap
  kExplore,    // θ_nn plus noise
  kExploit,    // θ_nn; updates the chosen module's interest
};

constexpr const char* to_string(EpisodeKind k) {
  switch (k) {
    case EpisodeKind::kNone:
      return "none";
    case EpisodeKind::kBootstrap:
      return "bootstrap";
    case EpisodeKind::kRandom:
      return "random";
    case EpisodeKind::kExplore:
      return "explore";
    case EpisodeKind::kExploit:
      return "exploit";
  }
  return "unknown";
}

// Fault and activity counters; reset by init().
struct ExplorerCounters {
  uint32_t proposals = 0;            // distinct episodes proposed
  uint32_t repeated_proposals = 0;   // propose() while an episode was pending
  uint32_t observations = 0;         // outcomes stored
  uint32_t out_of_order = 0;         // observe() with nothing pending
  uint32_t non_finite_outcomes = 0;  // observe() rejected for NaN/inf
  uint32_t archive_rejections = 0;   // archive append failed (cannot happen after init's check)
  uint32_t nn_queries = 0;           // nearest-neighbour scans
  uint32_t random_fallbacks = 0;     // goal episodes given θ ~ U for lack of 2 distinct outcomes
  uint32_t steps = 0;                // goal-exploration steps started
};

class Explorer {
 public:
  static constexpr uint64_t kStreamModuleChoice = 1;
  static constexpr uint64_t kStreamGoal = 2;
  static constexpr uint64_t kStreamRandomTheta = ThetaGenerator::kStreamRandomTheta;
  static constexpr uint64_t kStreamNoise = ThetaGenerator::kStreamNoise;
  static constexpr uint64_t kStreamFrontier = 5;

  // Validates `config` (see validate()) and starts a run from episode 0; on error the explorer is left
  // uninitialised. No heap use.
  Status init(const ExplorerConfig& config);

  // Writes the θ of the current episode. kNotInitialised, kDone, kInvalidArgument (null).
  Status propose(float theta[kThetaDim]);

  // Stores the outcome (config.outcome_dim values) of the pending episode and advances.
  // kNotInitialised, kNoPendingEpisode, kNonFiniteOutcome, kInvalidArgument (null).
  Status observe(const float* outcome);

  // Learned goal spaces that are retrained during the run (host_tools/online): swaps in the
  // retrained goal modules (config.modules, n_modules, algorithm, goal kind and bound) and rewrites
  // every archived outcome (outcomes: size() × outcome_dim floats, row-major, the archive's
  // episodes re-encoded), keeping all the rest: the archive's θ recipes (what was executed),
  // the four PRNG streams' positions, the episode count and the counters. Each module's
  // distinct-outcome state is rebuilt from the re-encoded outcomes and the interest model restarts
  // with cp = progress[k] (goal history emptied: its goals were in the old space).
  // Only between steps (not pending; a bootstrap episode or the first of a step is next) and
  // with the same seed, σ, D, W, ε, measure, bootstrap, episodes, outcome_dim and tie rule:
  // kInvalidArgument otherwise (also for null pointers, non-finite outcomes, RPE); a config
  // validate() rejects gives its status. On error nothing changes.
  // Replaying the run into a just-initialised Explorer with the re-encoded outcomes would NOT do this: its
  // nearest-neighbour queries, hence its θ, would differ from what the arm executed.
  Status rebase(const ExplorerConfig& config, const float* outcomes, const float* progress);

  // An outside choice of where to explore (host_tools/online's novelty steps): the next
  // goal-exploration step explores around archive entry `source` instead of around the 1-NN
  // of a sampled goal. That step draws no module and no goal (module() is -1 and the module
  // choice and goal streams do not advance), its 4 explore episodes add noise to θ_source as
  // usual (noise stream), and its exploit re-runs θ_source and updates no interest.
  // Only between steps of RGE/MGE after the bootstrap (the next episode starts a step) and
  // for 0 ≤ source < episode(): kInvalidArgument otherwise, and nothing changes.
  // Same seed, same outcomes and the same explore_around calls → the same θ, bit for bit.
  Status explore_around(int source);

  bool initialised() const { return initialised_; }
  bool done() const { return initialised_ && archive_.size() >= total_episodes_; }
  bool pending() const { return pending_; }

  // Index of the current episode (pending, or next to be proposed) = its archive index.
  int episode() const { return archive_.size(); }
  int total_episodes() const { return total_episodes_; }
  EpisodeKind kind() const;

  // The current (or last) goal-exploration step: chosen module (-1 before the first step),
  // its goal (goal_dim() values) and the archive index θ came from (-1: random θ).
  int module() const { return module_; }
  const float* goal() const { return goal_; }
  int goal_dim() const { return module_ < 0 ? 0 : modules_[module_].n_dims; }
  int source_episode() const { return source_; }
  // p of the last exploit (SPEC §2.5), 0 before the first.
  float last_progress() const { return last_progress_; }

  int n_modules() const { return n_modules_; }
  const GoalModule& goal_module(int k) const { return modules_[k]; }
  float interest(int k) const { return interest_.interest(k); }
  bool module_has_two_outcomes(int k) const { return distinct_[k].has_two(); }

  const ExplorerConfig& config() const { return config_; }
  const Archive& archive() const { return archive_; }
  const InterestModel& interest_model() const { return interest_; }
  const ExplorerCounters& counters() const { return counters_; }

 private:
  EpisodeKind kind_of(int episode) const;
  void random_theta();    // the pending θ ← the next random θ number
  int query(int module);  // θ_nn index for the current goal, -1 → random θ
  void start_step();

  Archive archive_;
  InterestModel interest_;
  GoalModule modules_[kMaxModules];
  DistinctOutcomes distinct_[kMaxModules];
  ExplorerConfig config_;
  Prng choice_rng_, goal_rng_, frontier_rng_;
  FrontierGoals frontier_;
  float pending_theta_[kThetaDim] = {};
  ThetaRecipe pending_recipe_;
  int random_thetas_ = 0;  // random θ numbers used so far (ThetaGenerator)
  int noise_vectors_ = 0;  // explore noise numbers used so far
  float goal_[kMaxOutcomeDim] = {};
  ExplorerCounters counters_;
  int n_modules_ = 0;
  int total_episodes_ = 0;
  int module_ = -1;
  int step_nn_ = -1;
  // θ of step_nn_, regenerated once per step: the step's 4 explore episodes (and its exploit,
  // when the re-query finds the same entry) start from it.
  float step_theta_[kThetaDim] = {};
  int source_ = -1;
  int directed_source_ = -1;  // explore_around() for the next step, -1: none
  bool directed_step_ = false;  // the current step came from explore_around()
  float last_progress_ = 0.0f;
  bool initialised_ = false;
  bool pending_ = false;
};

}  // namespace curio
