// `curio-lab run` and `curio-lab paper`: a campaign on this machine into --out (resumable,
// journaled, stopped cleanly by Ctrl-C: local_campaign.hpp), or with --task I --tasks N one
// task's share into a task folder for `merge` (campaign_task.hpp). `paper` is `run` with the
// paper's whole figure as its defaults.
#pragma once
#include <CLI/CLI.hpp>

#include "host_tools/lab/campaign_options.hpp"

namespace curio::lab {

struct RunCommandOptions {
  bool json = false;
  bool replace = false;
  bool no_journal = false;
  int task = -1;  // with tasks > 0: run --task I --tasks N
  int tasks = 0;
  bool efr_only = false;  // paper --efr-only
};

CLI::App* add_run_command(CLI::App& app, CampaignOptions& campaign, RunCommandOptions& options);
CLI::App* add_paper_command(CLI::App& app, CampaignOptions& campaign, RunCommandOptions& options);

// Exit status: 0; 1 a runtime failure or a failed run; 2 a usage error; 130/143 stopped.
int run_command(const CLI::App& command, const CampaignOptions& campaign,
                const RunCommandOptions& options);
int paper_command(const CLI::App& command, CampaignOptions campaign,
                  const RunCommandOptions& options);

}  // namespace curio::lab
