// `curio-sim rollout`: θ vectors on stdin, one final state per θ on stdout, all in one
// persistent world (the distractor stream continues from line to line).
#pragma once
#include <cstdint>
#include <cstdio>
#include <istream>
#include <string>

#include <CLI/CLI.hpp>

namespace curio::sim {

struct RolloutOptions {
  std::string physics = "kinematic";
  uint64_t seed = 0;
  double grasp_radius = 0.1;
  double distractor_noise = 0.1;
};

CLI::App* add_rollout_command(CLI::App* app, RolloutOptions* options);

// Exit status: 0 on success, 2 on a bad input line (message on err). The options are checked
// when parsed (add_rollout_command).
int run_rollout(const RolloutOptions& options, std::istream& in, std::FILE* out, std::FILE* err);

}  // namespace curio::sim
