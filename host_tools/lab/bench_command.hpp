// `curio-lab bench`: episodes per second of one core for each physics (one MGE-EFR run), with
// --per-algorithm the rate of each algorithm (the resource advice of docs/cluster.md), then the
// wall time of a whole campaign on --threads.
#pragma once
#include <CLI/CLI.hpp>

#include "host_tools/lab/campaign_options.hpp"

namespace curio::lab {

struct BenchCommandOptions {
  int ode_episodes = 2000;
  bool skip_campaign = false;
  bool per_algorithm = false;
};

CLI::App* add_bench_command(CLI::App& app, CampaignOptions& campaign, BenchCommandOptions& options);

// Exit status: 0; 2 a usage error.
int bench_command(const CLI::App& command, CampaignOptions campaign,
                  const BenchCommandOptions& options);

}  // namespace curio::lab
