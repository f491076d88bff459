// curio-sim: the Arm-2-Balls world on the command line. Subcommands: rollout, render, serve
// (the arm as CAN nodes on a bus, sim/serve/). Exit codes as every Curio program (README,
// "Command-line convention"): 2 for a usage error, 1 for a runtime failure, 130/143 when a
// signal stops serve.
#include <cstdio>
#include <iostream>

#include <CLI/CLI.hpp>

#include "host_tools/cli/command_line.hpp"
#include "sim/cli/render_command.hpp"
#include "sim/cli/rollout_command.hpp"
#include "sim/cli/serve_command.hpp"

int main(int argc, char** argv) {
  CLI::App app{"curio-sim: the Arm-2-Balls world of Curio (kinematic model, ODE arm, renderer)",
               "curio-sim"};
  app.require_subcommand(1);
  curio::sim::RolloutOptions rollout_options;
  curio::sim::RenderOptions render_options;
  CLI::App* rollout = curio::sim::add_rollout_command(&app, &rollout_options);
  CLI::App* render = curio::sim::add_render_command(&app, &render_options);
  curio::sim::ServeCommandOptions serve_options;
  CLI::App* serve = curio::sim::add_serve_command(&app, &serve_options);
  if (const auto code = curio::cli::parse(app, argc, argv)) return *code;
  if (*rollout) {
    std::ios::sync_with_stdio(false);
    return curio::sim::run_rollout(rollout_options, std::cin, stdout, stderr);
  }
  if (*render) return curio::sim::run_render(render_options, stderr);
  if (*serve) return curio::sim::run_serve(serve_options, stderr);
  return 2;
}
