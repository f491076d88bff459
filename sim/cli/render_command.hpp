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
  std::string output;
  int scale = 1;
};

CLI::App* add_render_command(CLI::App* app, RenderOptions* options);

// Exit status: 0 on success, 2 on a bad option, 1 when the file cannot be written.
int run_render(const RenderOptions& options, std::FILE* err);

}  // namespace curio::sim
