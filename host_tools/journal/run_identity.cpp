// A run's journal identity (host_tools/journal/run_identity.hpp).
#include "host_tools/journal/run_identity.hpp"

#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "firmware/explore/fnv1a.hpp"
#include "host_tools/experiment/explore_strategies.hpp"
#include "host_tools/experiment/representations.hpp"
#include "sim/world_identity.hpp"

namespace curio::journal::host {

namespace {

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

const char* physics_name(uint8_t p) {
  return p == 0 ? "kinematic" : p == 1 ? "ODE" : "unknown (real arm)";
}

// The explore strategy by its curio-lab name when it is one, else by its ingredients.
std::string strategy_text(const RunIdentity& id) {
  for (const lab::ExploreStrategy& st : lab::explore_strategies()) {
    bool same = std::memcmp(&st.frontier_share, &id.frontier_share, sizeof(float)) == 0;
    for (int i = 0; i < kExploreEpisodesPerStep; ++i)
      same = same && std::memcmp(&st.sigma_ladder[i], &id.sigma_ladder[i], sizeof(float)) == 0;
    if (same) return st.name;
  }
  return "frontier share " + number(id.frontier_share) + ", σ ladder ×(" +
         number(id.sigma_ladder[0]) + "," + number(id.sigma_ladder[1]) + "," +
         number(id.sigma_ladder[2]) + "," + number(id.sigma_ladder[3]) + ")";
}

std::string field_value(const RunIdentity& id, IdentityField f) {
  switch (f) {
    case IdentityField::kAlgorithmName:
      return id.algorithm_name;
    case IdentityField::kAlgorithm:
      return std::to_string(id.algorithm);
    case IdentityField::kSeed:
      return std::to_string(id.seed);
    case IdentityField::kSigma:
      return number(id.sigma);
    case IdentityField::kBootstrap:
      return std::to_string(id.n_bootstrap);
    case IdentityField::kEpisodes:
      return std::to_string(id.n_episodes);
    case IdentityField::kCompetenceCap:
      return number(id.competence_cap);
    case IdentityField::kCompetenceMeasure:
      return id.competence_measure == 0 ? "clip" : "scale";
    case IdentityField::kWindow:
      return number(id.window);
    case IdentityField::kEpsilon:
      return number(id.epsilon);
    case IdentityField::kGoalBound:
      return number(id.goal_bound);
    case IdentityField::kGoalKind:
      return id.goal_kind == 0 ? "uniform box" : "clipped normal";
    case IdentityField::kOutcomeDim:
      return std::to_string(id.outcome_dim);
    case IdentityField::kModules: {
      char b[48];
      std::snprintf(b, sizeof b, "%d modules (layout %08x)", id.n_modules,
                    static_cast<unsigned>(id.modules_hash));
      return b;
    }
    case IdentityField::kTieRule:
      return id.tie_rule == static_cast<uint8_t>(TieRule::kLatest) ? "latest" : "earliest";
    case IdentityField::kRequeryExploit:
      return id.requery_exploit ? "on" : "off";
    case IdentityField::kPhysics:
      return physics_name(id.physics);
    case IdentityField::kWeights:
    case IdentityField::kEnvironment: {
      char b[16];
      std::snprintf(b, sizeof b, "%08x",
                    static_cast<unsigned>(f == IdentityField::kWeights ? id.weights_hash
                                                                       : id.environment_hash));
      return b;
    }
    case IdentityField::kStrategy:
      return strategy_text(id);
    case IdentityField::kNone:
      break;
  }
  return "";
}

}  // namespace

RunIdentity identity_of(const lab::RunSpec& spec, const ExplorerConfig& config, uint8_t physics,
                        uint32_t environment_hash) {
  if (config.goal_scale != 1.0f)
    throw std::invalid_argument("the journal's run identity has no goal-scale field: "
                                "journal only runs with goal_scale 1");
  RunIdentity id;
  id.seed = config.seed;
  id.n_bootstrap = static_cast<uint32_t>(config.n_bootstrap);
  id.n_episodes = static_cast<uint32_t>(config.n_episodes);
  id.sigma = config.sigma;
  id.competence_cap = config.competence_cap;
  id.window = config.window;
  id.epsilon = config.epsilon;
  id.goal_bound = config.goal_bound;
  id.algorithm = static_cast<uint8_t>(config.algorithm);
  id.outcome_dim = static_cast<uint8_t>(config.outcome_dim);
  id.n_modules = static_cast<uint8_t>(config.n_modules);
  id.goal_kind = static_cast<uint8_t>(config.goal_kind);
  id.competence_measure = static_cast<uint8_t>(config.competence_measure);
  id.tie_rule = static_cast<uint8_t>(config.tie_rule);
  id.requery_exploit = config.requery_exploit ? 1 : 0;
  id.physics = physics;
  Fnv1a m;
  for (int k = 0; k < config.n_modules && k < kMaxModules; ++k) {
    m.add_u32(static_cast<uint32_t>(config.modules[k].n_dims));
    for (int d = 0; d < config.modules[k].n_dims; ++d) m.add_u32(config.modules[k].dims[d]);
  }
  id.modules_hash = m.h;
  if (spec.algorithm.outcome == lab::OutcomeSource::kLatents) {
    // The weights by their provenance (the trainer's input hash) and name.
    Fnv1a w;
    const lab::Representation* rep = lab::find_representation(spec.algorithm.representation);
    const std::string tag =
        spec.algorithm.representation + ":" + (rep ? rep->inputs_sha256 : std::string("missing"));
    for (char c : tag) w.add_u32(static_cast<uint8_t>(c));
    id.weights_hash = w.h;
  }
  id.environment_hash = environment_hash;
  id.frontier_share = config.frontier_share;
  for (int i = 0; i < kExploreEpisodesPerStep; ++i) id.sigma_ladder[i] = config.sigma_ladder[i];
  std::strncpy(id.algorithm_name, spec.algorithm.name.c_str(), kAlgorithmNameBytes - 1);
  return id;
}

std::string describe_difference(const RunIdentity& journal, const RunIdentity& run) {
  const IdentityField f = first_difference(journal, run);
  if (f == IdentityField::kNone) return "";
  const std::string name = to_string(f);
  return "journal is " + name + " " + field_value(journal, f) + ", this run is " + name + " " +
         field_value(run, f);
}

std::string describe(const RunIdentity& id) {
  const std::string strategy = has_strategy(id) ? " (explore " + strategy_text(id) + ")" : "";
  return std::string(id.algorithm_name) + strategy + " seed " + std::to_string(id.seed) + " σ " +
         number(id.sigma) + ", " + std::to_string(id.n_bootstrap) + " + " +
         std::to_string(id.n_episodes) + " episodes";
}

protocol::WorldIdentity asked_world(const lab::RunSpec& spec, uint8_t physics) {
  protocol::WorldIdentity w = sim::world_identity(spec.physics, spec.world, spec.explorer.seed);
  w.physics = physics;
  return w;
}

RunIdentity arm_run_identity(const lab::RunSpec& spec, const ExplorerConfig& config,
                             uint8_t physics) {
  return identity_of(spec, config, physics, protocol::world_hash(asked_world(spec, physics)));
}

}  // namespace curio::journal::host
