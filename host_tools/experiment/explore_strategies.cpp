#include "host_tools/experiment/explore_strategies.hpp"

namespace curio::lab {

const std::vector<ExploreStrategy>& explore_strategies() {
  static const std::vector<ExploreStrategy> kStrategies = {
      {"spec", 0.0f, {0, 0, 0, 0}, "SPEC §2.2-2.3 exactly (the default)"},
      {"beyond", 0.5f, {1, 2, 2, 4},
       "frontier goals in half the steps, explore noise σ×(1,2,2,4) over a step's 4 episodes"},
      {"beyond-without-frontier", 0.0f, {1, 2, 2, 4}, "beyond's σ ladder alone"},
      {"beyond-without-ladder", 0.5f, {0, 0, 0, 0}, "beyond's frontier goals alone, σ flat"},
      {"beyond-flat-sigma", 0.5f, {2, 2, 2, 2},
       "beyond's frontier goals with σ×2 on every explore episode"},
  };
  return kStrategies;
}

std::optional<ExploreStrategy> find_explore_strategy(const std::string& name) {
  for (const auto& s : explore_strategies())
    if (name == s.name) return s;
  return std::nullopt;
}

std::string explore_strategy_names() {
  std::string out;
  for (const auto& s : explore_strategies()) out += (out.empty() ? "" : ", ") + std::string(s.name);
  return out;
}

void apply_explore_strategy(const ExploreStrategy& s, ExplorerConfig* config) {
  config->frontier_share = s.frontier_share;
  for (int i = 0; i < 4; ++i) config->sigma_ladder[i] = s.sigma_ladder[i];
}

}  // namespace curio::lab
