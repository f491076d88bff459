// Bringing the arm up for a run over the bus: the firmware Controller initialised on the bus
// with the run's explorer (and encoder, for a learned goal space), the arm started (the
// controller's heartbeat, NMT reset and start, every node's identity, heartbeat, safety and CSP
// objects by SDO, the CiA 402 enable sequence; no PDO mapping and no homing: docs/hil.md), then what the camera node says about its world read and checked: its
// physics, whether its scenes are a function of (seed, episode), and its world against the
// run's (arm_world.hpp).
#pragma once
#include <cstdint>
#include <string>

#include "firmware/app/controller.hpp"
#include "hal/can_bus.hpp"
#include "host_tools/controller/bus_run_types.hpp"

namespace curio::app::host {

// Initialises `controller` on `bus` and starts the arm. Sets out->physics,
// out->episode_indexed and out->run.spec.physics. false with out->run.error (and
// out->counters) when the controller cannot start, the arm does not come up, or its world is not
// the run's; a start that got as far as the arm ends with a controlled stop (out->stop).
// `stop_signal`: the host's stop request (bus_run.hpp).
bool bring_up_arm(hal::CanBus* bus, const ControllerConfig& config, Explorer& explorer,
                  nn::Encoder* encoder, CycleProbe* probe, const volatile int* stop_signal,
                  Controller& controller, BusRunResult* out);

}  // namespace curio::app::host
