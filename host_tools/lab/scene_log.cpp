#include "host_tools/lab/scene_log.hpp"

#include <cstdio>
#include <filesystem>

#include "host_tools/common/atomic_file.hpp"
#include "host_tools/experiment/report.hpp"

namespace curio::lab {

std::string scenes_csv(const RunResult& r) {
  std::string out = "episode,ball_x,ball_y,distractor_x,distractor_y\n";
  out.reserve(out.size() + 48 * r.final_ball.size());
  char row[128];
  for (size_t i = 0; i < r.final_ball.size() && i < r.final_distractor.size(); ++i) {
    std::snprintf(row, sizeof row, "%zu,%.9g,%.9g,%.9g,%.9g\n", i,
                  static_cast<double>(r.final_ball[i][0]), static_cast<double>(r.final_ball[i][1]),
                  static_cast<double>(r.final_distractor[i][0]),
                  static_cast<double>(r.final_distractor[i][1]));
    out += row;
  }
  return out;
}

std::string scene_log_path(const std::string& out_dir, const RunSpec& spec) {
  return (std::filesystem::path(out_dir) / "runs" / (run_stem(spec) + "_scenes.csv")).string();
}

bool write_scene_log(const std::string& out_dir, const RunResult& r, std::string* error) {
  if (!r.error.empty()) return true;
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(out_dir) / "runs", ec);
  return host::write_file_atomically(scene_log_path(out_dir, r.spec), scenes_csv(r), error);
}

bool write_scene_logs(const std::string& out_dir, const std::vector<RunResult>& results,
                      std::string* error) {
  for (const auto& r : results)
    if (!write_scene_log(out_dir, r, error)) return false;
  return true;
}

}  // namespace curio::lab
