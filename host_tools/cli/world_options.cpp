#include "host_tools/cli/world_options.hpp"

#include "host_tools/cli/command_line.hpp"

namespace curio::sim {

void add_physics_option(CLI::App* cmd, std::string* physics) {
  cmd->add_option("--physics", *physics, "kinematic (reference model) or ode")
      ->check(CLI::IsMember({"kinematic", "ode"}))
      ->capture_default_str();
}

void add_world_params_options(CLI::App* cmd, double* grasp_radius, double* distractor_noise) {
  cmd->add_option("--grasp-radius", *grasp_radius,
                  "the ball is grasped when the hand is strictly closer than this")
      ->check(cli::kNonNegative)
      ->capture_default_str();
  cmd->add_option("--distractor-noise", *distractor_noise,
                  "std of the distractor's per-step random walk (0: it stays put)")
      ->check(cli::kNonNegative)
      ->capture_default_str();
}

void add_seed_option(CLI::App* cmd, uint64_t* seed, const std::string& help) {
  cmd->add_option("--seed", *seed, help)->check(cli::kSeed)->capture_default_str();
}

}  // namespace curio::sim
