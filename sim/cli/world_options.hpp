// The world's command-line options that curio-sim rollout and serve share: --physics,
// --grasp-radius and --distractor-noise, registered and checked in one place.
#pragma once
#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>

namespace curio::sim {

// --physics: kinematic or ode (default shown).
void add_physics_option(CLI::App* cmd, std::string* physics);

// --grasp-radius and --distractor-noise (defaults shown).
void add_world_params_options(CLI::App* cmd, double* grasp_radius, double* distractor_noise);

// Both must be finite and >= 0; otherwise a message on err and false.
bool check_world_params(double grasp_radius, double distractor_noise, std::FILE* err);

}  // namespace curio::sim
