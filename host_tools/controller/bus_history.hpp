// What the bus did to a run across processes (issue 15 item 6: faults never disappear
// silently). A killed controller's counters die with it; a resumed run would then report only
// its last process's faults, replays and node reboots. So the counters that judge a run are
// kept in --out/bus_counters.json, rewritten atomically whenever they change: the sum over
// every process of the run so far. A resume starts from that sum.
// Not kept: what happened during the episode in flight at a SIGKILL (it is run again).
#pragma once
#include <cstdint>
#include <string>

#include "firmware/app/controller_types.hpp"

namespace curio::app::host {

inline constexpr const char* kBusHistoryFileName = "bus_counters.json";

struct BusHistory {
  uint64_t processes = 0;  // controller processes that ran episodes of this run
  uint64_t faults[kFaultKinds] = {};
  uint64_t fault_total = 0;
  uint64_t replays = 0;
  uint64_t capture_retries = 0;
  uint64_t node_reboots = 0;
};

// The history in `path`; an absent file is an empty history (a run not resumed yet). false
// with *error for a file that exists but cannot be read as one.
bool load_bus_history(const std::string& path, BusHistory* history, std::string* error);

// earlier + this process's counters (this process counted once).
BusHistory combined(const BusHistory& earlier, const ControllerCounters& now);

// Writes `history` to `path` atomically (temp file, fsync, rename).
bool save_bus_history(const std::string& path, const BusHistory& history, std::string* error);

}  // namespace curio::app::host
