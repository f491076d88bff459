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

// "0x8611 from node 3 (following error)".
std::string emcy_text(uint16_t code, uint8_t node);
// "SIGTERM", "SIGINT", "SIGHUP".
std::string signal_name(int signo);
// One line on how the controlled stop went (controlled_stop.hpp).
std::string stop_report_text(const StopReport& r);

// Why the arm did not come up at start (start_arm returned s, no fatal fault): the faults, and
// what they point to. A node whose heartbeat said operational and then not, with nothing of
// ours between, is named as two nodes answering as it (a second curio-sim serve whose
// heartbeats interleave with the first's: under load its stale pre-operational heartbeat,
// or its boot-up after our reset, can come after the first's operational one) or a node that
// left operational on an error or restarted.
std::string bring_up_failure_text(const ControllerCounters& c, AppStatus s);

// Why run_episode returned s (not kOk), for the user: the fatal fault, or the faults and
// whether every attempt ran with the arm back between them (the faults recur: a second arm
// booting on the bus, a drive that faults on every try) or the arm did not come back within
// the hold time.
std::string episode_failure_text(const Controller& controller, AppStatus s,
                                 const ControllerConfig& config);

}  // namespace curio::app::host
