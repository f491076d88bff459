// The final scene of every episode of a run (ball and distractor positions), as a CSV: the
// images the agent saw, re-rendered later by the trainer (curio-train train --scenes).
#pragma once
#include <string>
#include <vector>

#include "host_tools/experiment/run.hpp"

namespace curio::lab {

// "episode,ball_x,ball_y,distractor_x,distractor_y" then one row per episode (0-based), the
// floats written with 9 significant digits so they read back exactly.
std::string scenes_csv(const RunResult& r);

// <out_dir>/runs/<run>_scenes.csv.
std::string scene_log_path(const std::string& out_dir, const RunSpec& spec);

// Writes scene_log_path of a successful run (atomically: atomic_file.hpp), as soon as it
// finishes (curio-lab run drops the run's scenes from memory after). false with *error on an
// I/O failure.
bool write_scene_log(const std::string& out_dir, const RunResult& r, std::string* error);

// write_scene_log for every successful run.
bool write_scene_logs(const std::string& out_dir, const std::vector<RunResult>& results,
                      std::string* error);

}  // namespace curio::lab
