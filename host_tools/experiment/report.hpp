// What a campaign leaves behind in its output folder:
//   runs/<algo>_sigma<σ>_seed<s>.csv     ratio and grasps at every recorded checkpoint
//   runs/<algo>_sigma<σ>_seed<s>_interest.csv   every module's interest vs episodes
//   runs/<algo>_sigma<σ>_seed<s>_scenes.csv     every episode's final scene (--save-scenes)
//   summary.json                         per algorithm, σ and checkpoint: mean, std, 95 % CI
//   summary.md                           the same at SPEC §4's columns, beside the reference
//   summary.csv                          every checkpoint, beside the paper's value
//   controllability.csv                  per run and module: the controllable-feature statistic
//   ratio_sigma<σ>.png                   ratio vs episodes, 95 % band per algorithm
//   interest_<algo>_sigma<σ>.png         mean interest of each module vs episodes
//   ball_positions_<algo>_sigma<σ>.png   final ball positions of the first seed
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "host_tools/experiment/campaign_config.hpp"

namespace curio::lab {

// A run's file stem in runs/: "<algo>_sigma<σ>_seed<s>" (also its name in task manifests).
std::string run_stem(const RunSpec& spec);

nlohmann::json summarize_campaign(const CampaignConfig& config,
                                  const std::vector<RunResult>& results, double wall_seconds);

// Writes every file listed above (but the scenes: host_tools/lab/scene_log.hpp); returns false
// with *error if a file cannot be written, a plot included (a full disk, a gnuplot error). Only
// a machine without gnuplot gets a warning in *warnings (the plot data and scripts are kept).
// Each file is written atomically (host_tools/common/atomic_file.hpp): a kill leaves the old
// file or the new one. `written`
// (optional) gets the path of every file written.
bool write_report(const CampaignConfig& config, const std::vector<RunResult>& results,
                  const nlohmann::json& summary, std::vector<std::string>* warnings,
                  std::string* error, std::vector<std::string>* written = nullptr);

// Every file, relative to the output folder, that write_report and the scene logs may write
// for a campaign of `config` (whatever its results): what `curio-lab run --replace` removes
// of an old campaign, and only that (host_tools/lab/local_campaign.hpp).
std::vector<std::string> report_files(const CampaignConfig& config);

// The table printed at the end of a campaign: mean ± std at SPEC §4's columns + reference.
std::string format_table(const nlohmann::json& summary);

}  // namespace curio::lab
