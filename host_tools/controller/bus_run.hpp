// One exploration run driven over a CAN bus by the firmware Controller, recorded exactly as
// curio-lab records an in-process run (lab::RunResult: checkpoints, ratio, grasps, interest,
// exploits, verdicts), so the same report code writes the same result files.
//
// run_over_bus does its jobs in this order: the journal is opened and a resume checked before
// anything moves (bus_journal.hpp; the run's identity: host_tools/journal/run_identity.hpp);
// the arm is brought up and its world checked (arm_bring_up.hpp); the journal is started or
// replayed; the episodes run (bus_run.cpp), the fault counters kept across processes
// (bus_history.hpp); the run is closed (its verdicts, and whether a fault may have changed its
// results). The result files are written by the caller (curio-controller: bus_report.hpp).
// The options and result types: bus_run_types.hpp.
#pragma once
#include <functional>

#include "hal/can_bus.hpp"
#include "host_tools/controller/bus_run_types.hpp"

namespace curio::app::host {

// Runs spec.explorer.n_bootstrap + n_episodes episodes against the arm on `bus`. `on_finish`
// (optional) sees the explorer at the end (parity tests compare its archive). Stops with
// run.error when another master or another arm shares the bus (fatal faults), when the arm
// reports another world (0x2003: seed, grasp radius, distractor noise, renderer; checked at the
// start and again after node reboots), or
// when the arm does not come back within the hold time.
BusRunResult run_over_bus(hal::CanBus* bus, const BusRunOptions& options,
                          const std::function<void(const Explorer&)>& on_finish = {});

}  // namespace curio::app::host
