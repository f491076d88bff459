// The end of `run`, `paper` and `merge`: the campaign's report written (summary, CSVs, plots:
// host_tools/experiment/report.hpp; the scene logs with --save-scenes) and its table printed,
// or the JSON summary with --json.
#pragma once
#include <vector>

#include <nlohmann/json.hpp>

#include "host_tools/experiment/campaign_config.hpp"

namespace curio::lab {

struct PrintReportOptions {
  bool json = false;            // the JSON summary on stdout instead of the table
  bool scenes_written = false;  // the scene logs are on disk already (a local run streams them)
};

// Returns the exit status: 1 when a file cannot be written (*written false) or a run failed,
// else 0. `written` (optional): whether every file was written.
int write_and_print_report(const CampaignConfig& campaign, const std::vector<RunResult>& results,
                           const nlohmann::json& summary, double wall_seconds,
                           const PrintReportOptions& options, bool* written = nullptr);

}  // namespace curio::lab
