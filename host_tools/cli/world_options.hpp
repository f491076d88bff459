// The command-line options of the simulated world, registered and checked in one place (curio-sim
// rollout and serve, curio-controller): the world's --physics, --grasp-radius and
// --distractor-noise, --seed, and the checks that make a bad value a usage error at parse time
// (exit 2, one line from main(), before anything runs or is written).
#pragma once
#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

namespace curio::sim {

// --physics: kinematic or ode (default shown).
void add_physics_option(CLI::App* cmd, std::string* physics);

// --grasp-radius and --distractor-noise (defaults shown), each a finite number >= 0.
void add_world_params_options(CLI::App* cmd, double* grasp_radius, double* distractor_noise);

// --seed: 0 to 2^64 - 1 (cli::kSeed; CLI11 alone would wrap "-1" to 2^64 - 1).
void add_seed_option(CLI::App* cmd, uint64_t* seed, const std::string& help);

}  // namespace curio::sim
