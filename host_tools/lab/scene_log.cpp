#include "host_tools/lab/scene_log.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "host_tools/lab/report.hpp"

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

bool write_scene_logs(const std::string& out_dir, const std::vector<RunResult>& results,
                      std::string* error) {
  const std::filesystem::path dir = std::filesystem::path(out_dir) / "runs";
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  for (const auto& r : results) {
    if (!r.error.empty()) continue;
    const auto path = dir / (run_stem(r.spec) + "_scenes.csv");
    std::ofstream f(path);
    if (!f || !(f << scenes_csv(r))) {
      *error = "cannot write " + path.string();
      return false;
    }
  }
  return true;
}

}  // namespace curio::lab
