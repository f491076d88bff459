// Run-time configuration of the Explorer (SPEC §2). Plain data; validate() checks it.
#pragma once
#include <cstdint>

#include "firmware/explore/config.hpp"
#include "firmware/explore/goal_module.hpp"
#include "firmware/explore/interest_model.hpp"
#include "firmware/explore/nearest_neighbour.hpp"
#include "firmware/explore/schedule.hpp"
#include "firmware/explore/status.hpp"

namespace curio {

enum class Algorithm : uint8_t {
  kRpe,  // random parameter exploration: θ ~ U[-1,1]^49 every episode
  kRge,  // random goal exploration: exactly 1 module
  kMge,  // modular goal exploration: 1..kMaxModules modules chosen by interest
};

// Which outcome dimensions make up each module (all other module fields come from the config).
struct ModuleDims {
  int n_dims = 0;
  uint8_t dims[kMaxOutcomeDim] = {};
};

struct ExplorerConfig {
  Algorithm algorithm = Algorithm::kMge;
  int outcome_dim = 4;  // values per observed outcome, 1..kMaxOutcomeDim
  int n_modules = 0;    // RPE: ignored; RGE: 1; MGE: 1..kMaxModules
  ModuleDims modules[kMaxModules] = {};
  GoalKind goal_kind = GoalKind::kUniformBox;
  float goal_bound = 2.5f;      // clip of kClippedNormal goals, > 0
  // kClippedNormal goals are scaled by this after the clip, > 0. 1 (SPEC §2.3) samples the
  // VAE prior; > 1 asks beyond it, for a goal space learned from the agent's own outcomes,
  // whose prior covers what was reached rather than the arena (host_tools/online).
  float goal_scale = 1.0f;
  float sigma = 0.05f;          // explore noise std on θ, ≥ 0
  float competence_cap = 2.0f;  // D of SPEC §2.5, > 0
  CompetenceMeasure competence_measure = CompetenceMeasure::kClipped;  // how D enters
  float window = 1000.0f;       // W of SPEC §2.5, ≥ 1
  float epsilon = 0.1f;         // uniform share of module choice, [0, 1]
  int n_bootstrap = 100;        // random episodes first, ≥ 0
  int n_episodes = 10000;       // episodes after bootstrap, multiple of 5 (RGE/MGE)
  uint64_t seed = 0;
  TieRule tie_rule = TieRule::kLatest;  // 1-NN ties in the archive (nearest_neighbour.hpp)
  // Exploit θ = NN of the goal in the archive as it is at the exploit episode (after the
  // step's 4 explore episodes), as the reference code does; false: reuse the step's θ_nn.
  bool requery_exploit = true;
  // Beyond SPEC (frontier_goals.hpp): the share of steps, in [0, 1], whose goal is drawn just
  // beyond what the chosen module has reached instead of from §2.3's distribution. 0 is
  // SPEC's algorithm, bit for bit (the frontier stream is then never drawn).
  float frontier_share = 0.0f;
  // Beyond SPEC (theta_generator.hpp): explore noise number x has std σ·sigma_ladder[x mod 4],
  // so a step's 4 explore episodes (4 consecutive numbers) take small and large steps alike.
  // All zero (default): σ for every episode, SPEC §2.2 bit for bit; else each in (0, 100].
  float sigma_ladder[kExploreEpisodesPerStep] = {};
};

// kOk, kInvalidConfig (a field out of range, a module dim ≥ outcome_dim or repeated within a
// module, the module count wrong for the algorithm) or kCapacityTooSmall
// (n_bootstrap + n_episodes > kArchiveCapacity).
Status validate(const ExplorerConfig& config);

// Whether sigma_ladder is set (any value non-zero).
bool has_sigma_ladder(const ExplorerConfig& config);

}  // namespace curio
