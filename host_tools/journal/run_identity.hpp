// A run's identity in its journal (firmware/journal/journal_format.hpp's RunIdentity),
// computed here and nowhere else: from the run's lab::RunSpec and Explorer config, the physics
// and, for a run on an arm, the world the run asks for (sim/world_identity.hpp, the same
// identity `curio-sim serve` publishes as camera 0x2003) as its environment hash. curio-lab's
// journals, curio-lab score, and curio-controller's journal and world check all take it from
// here, and a resume under another identity is refused with describe_difference's words.
#pragma once
#include <cstdint>
#include <string>

#include "firmware/explore/explorer_config.hpp"
#include "firmware/journal/journal_format.hpp"
#include "firmware/protocol/world_identity.hpp"
#include "host_tools/experiment/run.hpp"

namespace curio::journal::host {

// Identity of a run: its Explorer config, algorithm name, the goal space's weights (learned
// goal spaces: FNV-1a of the int8 model), physics (0 kinematic, 1 ODE, 0xFF unknown) and,
// when non-zero, a caller-defined environment hash. Throws std::invalid_argument for a config
// the identity cannot name (goal_scale ≠ 1: the format has no field for it, and a resume could
// not tell two such runs apart).
RunIdentity identity_of(const lab::RunSpec& spec, const ExplorerConfig& config, uint8_t physics,
                        uint32_t environment_hash = 0);

// "" when the same run, else e.g. "journal is seed 3, this run is seed 4".
std::string describe_difference(const RunIdentity& journal, const RunIdentity& run);
// "MGE-EFR seed 3 σ 0.05, 100 + 2000 episodes" (for messages).
std::string describe(const RunIdentity& id);
// The world `spec` asks for on an arm of `physics` (camera 0x2002's value): its seed, grasp
// radius, distractor noise and this build's renderer version.
protocol::WorldIdentity asked_world(const lab::RunSpec& spec, uint8_t physics);

// The identity of a run on an arm (curio-controller): identity_of with the hash of the world
// the run asks for as its environment hash.
RunIdentity arm_run_identity(const lab::RunSpec& spec, const ExplorerConfig& config,
                             uint8_t physics);

}  // namespace curio::journal::host
