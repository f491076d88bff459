// Bringing the arm up for a run over the bus: the firmware Controller initialised on the bus
// with the run's explorer (and encoder, for a learned goal space), the arm started (the
// controller's heartbeat, NMT reset and start, every node's identity, heartbeat, safety and CSP
// objects by SDO, the CiA 402 enable sequence; no PDO mapping and no homing: docs/hil.md), then what the camera node says about its world read and checked: its
// physics, whether its scenes are a function of (seed, episode), and its world against the
// run's (below).
//
// The arm's world against the run's: what `curio-sim serve` publishes as its world identity
// (camera 0x2003: run seed, grasp radius, distractor noise, renderer version and their hash;
// firmware/protocol/world_identity.hpp) read at bring-up and after node reboots, and compared
// field by field with the world the run asks for (its --seed, --grasp-radius,
// --distractor-noise, this build's renderer: journal::host::asked_world, run_identity.hpp). A run against another world is refused before
// its first episode, the message naming the field, both values and the fix. The physics is
// the arm's (0x2002): curio-controller takes it, and the journal's identity checks it on a
// resume. A real arm publishes no world: nothing to compare.
#pragma once
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "firmware/app/controller.hpp"
#include "firmware/protocol/world_identity.hpp"
#include "hal/can_bus.hpp"
#include "host_tools/controller/bus_run_types.hpp"
#include "host_tools/experiment/run.hpp"

namespace curio::app::host {

// Initialises `controller` on `bus` and starts the arm. Sets out->physics,
// out->episode_indexed and out->run.spec.physics. false with out->run.error (and
// out->counters) when the controller cannot start, the arm does not come up, or its world is not
// the run's; a start that got as far as the arm ends with a controlled stop (out->stop).
// `stop_signal`: the host's stop request (bus_run.hpp).
bool bring_up_arm(hal::CanBus* bus, const ControllerConfig& config, Explorer& explorer,
                  nn::Encoder* encoder, CycleProbe* probe, const volatile int* stop_signal,
                  Controller& controller, BusRunResult* out);


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
