// A run's explorer, built from its specification: the learned representation (if the goal
// space is one), the Explorer config with the algorithm's modules, the firmware Explorer
// initialised (one ~3 MB allocation, none during the run), and the int8 encoder a learned goal
// space needs (its activation arena is a member). Whoever runs the episodes starts from it: the
// simulated run (simulated_run.hpp) and curio-controller over the bus.
#pragma once
#include <memory>
#include <string>

#include "firmware/explore/explorer.hpp"
#include "firmware/nn/encoder.hpp"
#include "host_tools/experiment/representations.hpp"
#include "host_tools/experiment/run.hpp"

namespace curio::lab {

struct RunExplorer {
  const Representation* rep = nullptr;  // null: engineered features or RPE
  ExplorerConfig config;
  std::unique_ptr<Explorer> explorer;
  std::unique_ptr<nn::Encoder> encoder;  // learned goal spaces only
};

// false with *error: the weights of the run's goal space are missing from this build, the
// explorer rejects the configuration, or its init fails.
bool make_run_explorer(const RunSpec& spec, RunExplorer* run, std::string* error);

}  // namespace curio::lab
