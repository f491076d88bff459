// Named goal-exploration strategies: SPEC §2's loop ("spec", the default) and the strategies
// beyond it, each a set of ExplorerConfig ingredients (firmware/explore/frontier_goals.hpp,
// theta_generator.hpp). curio-lab's --explore picks one for every run of a campaign;
// docs/beyond.md says what each changes and what it measured.
//   spec                      SPEC §2.2–2.3 exactly (golden checksums)
//   beyond                    frontier goals in half the steps + σ ladder ×(1, 2, 2, 4)
//   beyond-without-frontier   the ladder alone
//   beyond-without-ladder     the frontier goals alone, σ flat
//   beyond-flat-sigma         frontier goals, σ ×2 on every explore episode (the ladder's
//                             larger steps without its spread)
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "firmware/explore/explorer_config.hpp"

namespace curio::lab {

struct ExploreStrategy {
  const char* name;
  float frontier_share;  // ExplorerConfig::frontier_share
  float sigma_ladder[4];  // ExplorerConfig::sigma_ladder (all 0: flat σ)
  const char* what;       // one line for --help and the report
};

const std::vector<ExploreStrategy>& explore_strategies();
std::optional<ExploreStrategy> find_explore_strategy(const std::string& name);
// "spec, beyond, ..." for messages and --help.
std::string explore_strategy_names();

// Puts the strategy's ingredients into `config` (the rest of it is left as it is).
void apply_explore_strategy(const ExploreStrategy& strategy, ExplorerConfig* config);

}  // namespace curio::lab
