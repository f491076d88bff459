// The campaign options that curio-lab's run, paper, bench and slurm commands share: the
// algorithms, seeds and physics (as text: lists and names), the exploration options every
// exploring program shares (exploration_options.hpp: σ list, bootstrap, D, W, ε, tie rule,
// strategy), and the world and the threads (bound straight into a CampaignConfig).
// build_campaign turns them into the campaign, or names the first option that cannot be used
// (a usage error: exit 2).
#pragma once
#include <string>

#include <CLI/CLI.hpp>

#include "host_tools/experiment/campaign_config.hpp"
#include "host_tools/experiment/exploration_options.hpp"

namespace curio::lab {

struct CampaignOptions {
  std::string algos = "RPE,RGE-EFR,MGE-EFR";
  std::string seeds = "0-2";
  std::string physics = "kinematic";
  ExplorationOptions exploration;  // σ list, bootstrap, D, competence, W, ε, tie rule, strategy
  CampaignConfig config;  // episodes, world, threads; out and quiet by command
};

void add_campaign_options(CLI::App* command, CampaignOptions& options);

// The campaign of `options`, checked (validate_campaign). false with *problem: one line, naming
// the option, for the first thing wrong.
bool build_campaign(const CampaignOptions& options, CampaignConfig* campaign, std::string* problem);

}  // namespace curio::lab
