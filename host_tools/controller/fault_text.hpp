// What the controller's faults mean, in words for the user: the one-line summary of a run's
// fault counters, the meaning of a fatal fault (another master, a second arm), and why an
// episode failed. curio-controller prints them; run_over_bus puts them in the run's error.
#pragma once
#include <string>

#include "firmware/app/controller.hpp"

namespace curio::app::host {

// One entry per fault kind that occurred, e.g. "feedback_timeout 2; last: ... (node 3)";
// "no faults" when none did.
std::string fault_summary(const ControllerCounters& c);

// What a fatal fault means, for the user: "another master is driving this arm ...".
std::string fatal_fault_text(const ControllerCounters& c, Fault fatal);

// Why run_episode returned s (not kOk), for the user: the fatal fault, or the faults and
// whether every attempt ran with the arm back between them (the faults recur: a second arm
// booting on the bus, a drive that faults on every try) or the arm did not come back within
// the hold time.
std::string episode_failure_text(const Controller& controller, AppStatus s,
                                 const ControllerConfig& config);

}  // namespace curio::app::host
