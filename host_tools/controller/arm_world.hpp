// The arm's world against the run's: what `curio-sim serve` publishes as its world identity
// (camera 0x2003: run seed, grasp radius, distractor noise, renderer version and their hash;
// firmware/protocol/world_identity.hpp) read at bring-up and after node reboots, and compared
// field by field with the world the run asks for (its --seed, --grasp-radius,
// --distractor-noise, this build's renderer: journal::host::asked_world, run_identity.hpp). A run against another world is refused before
// its first episode, the message naming the field, both values and the fix. The physics is
// the arm's (0x2002): curio-controller takes it, and the journal's identity checks it on a
// resume. A real arm publishes no world: nothing to compare.
#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "firmware/app/controller.hpp"
#include "firmware/protocol/world_identity.hpp"
#include "host_tools/experiment/run.hpp"

namespace curio::app::host {

// Reads the arm's world (0x2002 and 0x2003.1–8) into *arm. false when it has none (a real arm,
// or a node that does not answer: then bring-up has failed already). *damaged (optional):
// the eight words do not agree with their hash (a garbled read).
bool read_arm_world(Controller& controller, protocol::WorldIdentity* arm, bool* damaged = nullptr);

// "" when the arm's world is the one `spec` asks for (or the arm has none); else what differs
// ("the arm's world has grasp radius 0.3 but this run asks for 0.1") and how to fix it. *arm
// (optional) gets what the arm published; *published whether it published one.
std::string world_mismatch(Controller& controller, const lab::RunSpec& spec,
                           protocol::WorldIdentity* arm = nullptr, bool* published = nullptr);

// summary.json's "world": physics, seed, grasp radius, distractor noise, renderer version and
// the hash the journal's identity keeps (hex).
nlohmann::json world_json(const protocol::WorldIdentity& world);

}  // namespace curio::app::host
