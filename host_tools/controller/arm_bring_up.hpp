// Bringing the arm up for a run over the bus: the firmware Controller initialised on the bus
// with the run's explorer (and encoder, for a learned goal space), the arm started (NMT, PDO
// mapping, homing), then what the camera node says about its world read and checked: its
// physics, whether its scenes are a function of (seed, episode), and its run seed against the
// run's. Also the seed check again after node reboots (a rebooted node may run another world).
#pragma once
#include <cstdint>
#include <string>

#include "firmware/app/controller.hpp"
#include "hal/can_bus.hpp"
#include "host_tools/controller/bus_run.hpp"

namespace curio::app::host {

// Initialises `controller` on `bus` and starts the arm. Sets out->physics,
// out->episode_indexed and out->run.spec.physics. false with out->run.error (and
// out->counters) when the controller cannot start, the arm does not come up, or it runs another
// seed (then it is stopped again).
bool bring_up_arm(hal::CanBus* bus, const ControllerConfig& config, Explorer& explorer,
                  nn::Encoder* encoder, CycleProbe* probe, Controller& controller,
                  BusRunResult* out);

// The arm's run seed (camera 0x2003) against the run's: "" when they agree or the arm has none
// (a real arm); else what is wrong and how to fix it.
std::string seed_mismatch(Controller& controller, int64_t run_seed);

}  // namespace curio::app::host
