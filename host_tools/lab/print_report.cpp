#include "host_tools/lab/print_report.hpp"

#include <cstdio>
#include <iostream>

#include "host_tools/experiment/report.hpp"
#include "host_tools/lab/scene_log.hpp"

namespace curio::lab {

int write_and_print_report(const CampaignConfig& c, const std::vector<RunResult>& results,
                           const nlohmann::json& summary, double wall,
                           const PrintReportOptions& options, bool* written) {
  std::vector<std::string> warnings;
  std::string error;
  const bool ok = write_report(c, results, summary, &warnings, &error);
  if (written) *written = ok;
  if (!ok) {
    std::cerr << "curio-lab: " << error << '\n';
    return 1;
  }
  if (c.save_scenes && !options.scenes_written && !write_scene_logs(c.out_dir, results, &error)) {
    std::cerr << "curio-lab: " << error << '\n';
    return 1;
  }
  for (const auto& w : warnings) std::cerr << "curio-lab: warning: " << w << '\n';
  if (options.json) {
    std::cout << summary.dump(2) << '\n';
  } else {
    std::cout << "\nExploration ratio (mean ± std over seeds"
              << (c.explore == "spec" ? "" : ", strategy " + c.explore) << "):\n\n"
              << format_table(summary);
    std::printf("\nwall time %.1f s; results, CSVs and plots in %s/\n", wall, c.out_dir.c_str());
  }
  return summary["failed_runs"].get<int>() == 0 ? 0 : 1;
}

}  // namespace curio::lab
