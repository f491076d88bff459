#include "sim/cli/rollout_command.hpp"

#include <string>

#include "host_tools/cli/world_options.hpp"
#include "sim/cli/theta_line.hpp"
#include "sim/world.hpp"

namespace curio::sim {

CLI::App* add_rollout_command(CLI::App* app, RolloutOptions* options) {
  CLI::App* cmd = app->add_subcommand(
      "rollout",
      "Run one episode per θ read from stdin (49 numbers in [-1,1] per line, whitespace "
      "and/or comma separated; blank lines and '#' lines ignored) and print "
      "'grasped ball_x ball_y distractor_x distractor_y hand_x hand_y' of the final state");
  add_physics_option(cmd, &options->physics);
  add_seed_option(cmd, &options->seed, "seed of the distractor's random walk");
  add_world_params_options(cmd, &options->grasp_radius, &options->distractor_noise);
  return cmd;
}

int run_rollout(const RolloutOptions& options, std::istream& in, std::FILE* out, std::FILE* err) {
  Physics physics{};
  if (!parse_physics(options.physics, &physics)) {  // --physics is checked when parsed
    std::fprintf(err, "curio-sim: unknown physics '%s' (use kinematic or ode)\n",
                 options.physics.c_str());
    return 2;
  }
  WorldParams params;
  params.grasp_radius = options.grasp_radius;
  params.distractor_noise = options.distractor_noise;
  const auto world = make_world(physics, params, options.seed);

  std::string line;
  std::string error;
  float theta[kThetaDim];
  for (long line_number = 1; std::getline(in, line); ++line_number) {
    const ThetaLineStatus status = parse_theta_line(line, theta, &error);
    if (status == ThetaLineStatus::kSkip) continue;
    if (status == ThetaLineStatus::kError) {
      std::fflush(out);
      std::fprintf(err, "curio-sim: line %ld: %s\n", line_number, error.c_str());
      return 2;
    }
    const SceneState s = world->rollout(theta);
    std::fprintf(out, "%d %.17g %.17g %.17g %.17g %.17g %.17g\n", s.grasped ? 1 : 0, s.ball.x,
                 s.ball.y, s.distractor.x, s.distractor.y, s.hand.x, s.hand.y);
    // Line in, line out: usable as a coprocess.
    std::fflush(out);
  }
  return 0;
}

}  // namespace curio::sim
