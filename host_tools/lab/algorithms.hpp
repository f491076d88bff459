// The exploration algorithms curio-lab knows, by their names in the paper (SPEC §2.1), and
// how each one configures the firmware Explorer.
#pragma once
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "explore/explorer_config.hpp"

namespace curio::lab {

enum class OutcomeSource {
  kNone,                 // RPE: outcomes only feed the metric
  kEngineeredFeatures,   // [distractor x, y, ball x, y] at t = 49
};

struct AlgorithmSpec {
  std::string name;                 // "RPE", "RGE-EFR", "MGE-EFR"
  Algorithm algorithm;
  OutcomeSource outcome;
  int default_bootstrap;            // SPEC §2.2: 100 for EFR
  std::string description;
};

const std::vector<AlgorithmSpec>& known_algorithms();
std::optional<AlgorithmSpec> find_algorithm(std::string_view name);

// Fills algorithm, outcome dim, modules and goal kind of `config` for `spec`.
Status configure_modules(const AlgorithmSpec& spec, ExplorerConfig& config);

// Human-readable module names for plots ("distractor", "ball", "all").
std::vector<std::string> module_names(const AlgorithmSpec& spec);

}  // namespace curio::lab
