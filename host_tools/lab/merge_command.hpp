// `curio-lab merge DIR... --out OUT`: the task folders of a split campaign (run --task I
// --tasks N, or a Slurm array) back into one report, as a local run writes it
// (campaign_merge.hpp); missing and failed runs are listed, and refused unless --allow-partial.
#pragma once
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace curio::lab {

struct MergeCommandOptions {
  std::vector<std::string> dirs;
  std::string out;
  bool allow_partial = false;
  bool json = false;
};

CLI::App* add_merge_command(CLI::App& app, MergeCommandOptions& options);

// Exit status: 0; 1 runs missing or failed (without --allow-partial), or a file cannot be
// written; 2 the folders are not tasks of one campaign.
int merge_command(const CLI::App& command, const MergeCommandOptions& options);

}  // namespace curio::lab
