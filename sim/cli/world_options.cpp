#include "sim/cli/world_options.hpp"

#include <cmath>

namespace curio::sim {

void add_physics_option(CLI::App* cmd, std::string* physics) {
  cmd->add_option("--physics", *physics, "kinematic (reference model) or ode")
      ->check(CLI::IsMember({"kinematic", "ode"}))
      ->capture_default_str();
}

void add_world_params_options(CLI::App* cmd, double* grasp_radius, double* distractor_noise) {
  cmd->add_option("--grasp-radius", *grasp_radius,
                  "the ball is grasped when the hand is strictly closer than this")
      ->capture_default_str();
  cmd->add_option("--distractor-noise", *distractor_noise,
                  "std of the distractor's per-step random walk (0: it stays put)")
      ->capture_default_str();
}

bool check_world_params(double grasp_radius, double distractor_noise, std::FILE* err) {
  if (!std::isfinite(grasp_radius) || grasp_radius < 0.0) {
    std::fprintf(err, "curio-sim: --grasp-radius must be a finite number >= 0 (got %g)\n",
                 grasp_radius);
    return false;
  }
  if (!std::isfinite(distractor_noise) || distractor_noise < 0.0) {
    std::fprintf(err, "curio-sim: --distractor-noise must be a finite number >= 0 (got %g)\n",
                 distractor_noise);
    return false;
  }
  return true;
}

}  // namespace curio::sim
