// The exploration options, defined once for every program that explores: curio-lab (a campaign:
// several σ), curio-controller (one run on the arm: one σ) and curio-online (the strategy only:
// the rest of its explorer is its recipe, options.json). One spelling, one help text, one check
// each, bound to text first and turned into a CampaignConfig by apply_exploration_options:
//   --noise σ[,σ...]   --bootstrap N   --competence-clip D   --competence clip|scale
//   --window W         --epsilon ε     --tie-rule latest|earliest   --explore STRATEGY
//
//   lab::ExplorationOptions explore;
//   lab::add_exploration_options(&app, &explore, lab::ExplorationSet::kOneRun);
//   ...parse...
//   if (!lab::apply_exploration_options(explore, lab::ExplorationSet::kOneRun, &campaign, &problem))
//     return usage_error(problem);  // one line naming the option
#pragma once
#include <string>

#include <CLI/CLI.hpp>

#include "host_tools/experiment/campaign_config.hpp"

namespace curio::lab {

// Which of the options a program offers.
enum class ExplorationSet {
  kCampaign,      // all of them; --noise takes a list (curio-lab)
  kOneRun,        // all of them; --noise takes one σ (curio-controller)
  kStrategyOnly,  // --explore alone (curio-online)
};

struct ExplorationOptions {
  std::string noise = "0.05";
  int bootstrap = -1;              // < 0: each algorithm's default (SPEC §2.2)
  double competence_clip = -1.0;   // D; < 0: each algorithm's default
  std::string competence = "clip";
  double window = CampaignConfig{}.window;
  double epsilon = CampaignConfig{}.epsilon;
  std::string tie_rule = "latest";
  std::string explore = "spec";
};

void add_exploration_options(CLI::App* app, ExplorationOptions* options, ExplorationSet set);

// Writes the options of `set` into *campaign (sigmas, bootstrap, competence_clip,
// competence_measure, window, epsilon, tie_rule, explore). false with *problem, one line naming
// the option, for a value that is not one (a σ that is not a number, two σ for one run, an
// unknown --competence, --tie-rule or --explore); the ranges are validate_campaign's.
bool apply_exploration_options(const ExplorationOptions& options, ExplorationSet set,
                               CampaignConfig* campaign, std::string* problem);

}  // namespace curio::lab
