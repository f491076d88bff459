// The exploration algorithms curio-lab knows, by their names in the paper (SPEC §2.1), and
// how each one configures the firmware Explorer.
#pragma once
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "firmware/explore/explorer_config.hpp"

namespace curio::lab {

enum class OutcomeSource {
  kNone,                 // RPE: outcomes only feed the metric
  kEngineeredFeatures,   // [distractor x, y, ball x, y] at t = 49
  kLatents,              // μ of the int8 encoder on the final camera frame
};

struct AlgorithmSpec {
  std::string name;                 // "RPE", "MGE-EFR", "MGE-βVAE", ...
  Algorithm algorithm;
  OutcomeSource outcome;
  int default_bootstrap;            // SPEC §2.2: 100 for EFR, 400 for learned goal spaces
  double default_competence_clip;   // D: 1 reproduces the archived EFR runs, 2 the learned ones
  std::string representation;       // kLatents: "beta_vae" or "vae"
  int group_size = 0;               // kLatents: latents per module (2: 5 pairs, 1: 10, 10: RGE)
  std::string description;
};

const std::vector<AlgorithmSpec>& known_algorithms();
// Accepts the paper's names and ASCII spellings (MGE-bVAE, MGE-betaVAE for MGE-βVAE).
std::optional<AlgorithmSpec> find_algorithm(std::string_view name);

// Fills algorithm, outcome dim, modules and goal kind of `config` for `spec`.
// kLatents needs the representation's KL order (SPEC §2.4).
Status configure_modules(const AlgorithmSpec& spec, ExplorerConfig& config,
                         const uint8_t* kl_order = nullptr);

// Human-readable module names for plots: "distractor", "ball", "all", or the latents
// of each module ("z3+z7") given the KL order.
std::vector<std::string> module_names(const AlgorithmSpec& spec, const uint8_t* kl_order = nullptr);

}  // namespace curio::lab
