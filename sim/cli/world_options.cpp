#include "sim/cli/world_options.hpp"

#include <cmath>

namespace curio::sim {

const CLI::Validator kFiniteNonNegative(
    [](std::string& text) {
      double value = 0.0;
      const bool ok = CLI::detail::lexical_cast(text, value) && std::isfinite(value) && value >= 0.0;
      return ok ? std::string() : "'" + text + "' is not a finite number >= 0";
    },
    "NUMBER >= 0");

void add_physics_option(CLI::App* cmd, std::string* physics) {
  cmd->add_option("--physics", *physics, "kinematic (reference model) or ode")
      ->check(CLI::IsMember({"kinematic", "ode"}))
      ->capture_default_str();
}

void add_world_params_options(CLI::App* cmd, double* grasp_radius, double* distractor_noise) {
  cmd->add_option("--grasp-radius", *grasp_radius,
                  "the ball is grasped when the hand is strictly closer than this")
      ->check(kFiniteNonNegative)
      ->capture_default_str();
  cmd->add_option("--distractor-noise", *distractor_noise,
                  "std of the distractor's per-step random walk (0: it stays put)")
      ->check(kFiniteNonNegative)
      ->capture_default_str();
}

void add_seed_option(CLI::App* cmd, uint64_t* seed, const std::string& help) {
  cmd->add_option("--seed", *seed, help)
      ->check(CLI::Validator(
          [](std::string& text) {
            const bool digits =
                !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
            return digits ? std::string() : "'" + text + "' is not a whole number >= 0";
          },
          "SEED"))
      ->capture_default_str();
}

}  // namespace curio::sim
