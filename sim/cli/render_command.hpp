// `curio-sim render`: the 64×64 observation of one scene (SPEC §1.4) as a PNG.
#pragma once
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace curio::sim {

struct RenderOptions {
  std::vector<double> ball = {0.6, 0.6};
  std::vector<double> distractor = {0.7, -0.45};
  std::string png;  // --png FILE
  int scale = 1;
};

CLI::App* add_render_command(CLI::App* app, RenderOptions* options);

// Exit status: 0 on success, 1 when the file cannot be written. The options are checked when
// parsed (add_render_command: positions inside the arena, --scale 1..64).
int run_render(const RenderOptions& options, std::FILE* err);

}  // namespace curio::sim
