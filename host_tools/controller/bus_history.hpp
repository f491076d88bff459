// What the bus did to a run across processes, so that faults never disappear silently. A
// killed controller's counters die with it; a resumed run would then report only
// its last process's faults, replays and node reboots. So the counters that judge a run are
// kept in --out/bus_counters.json, rewritten atomically whenever they change: the sum over
// every process of the run so far. A resume starts from that sum.
// Not kept: what happened during the episode in flight at a SIGKILL (it is run again).
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>

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

// The history file of one controller process: the sum over the run's earlier processes
// (load_earlier, for a resumed run) plus this process's counters, rewritten whenever the
// counters that judge a run (faults, replays, capture retries, node reboots) change. An empty
// path keeps nothing. A write that fails is a warning line on `warnings` (when given): the run
// goes on.
class BusHistoryFile {
 public:
  BusHistoryFile(std::string path, std::FILE* warnings)
      : path_(std::move(path)), warnings_(warnings) {}

  // The earlier processes' sum from the file (an absent file: none). false with *error.
  bool load_earlier(std::string* error);
  // Writes earlier + now.
  void save(const ControllerCounters& now);
  // Writes earlier + now if the judging counters changed since the last write.
  void save_if_changed(const ControllerCounters& now);
  // earlier + now.
  BusHistory total(const ControllerCounters& now) const { return combined(earlier_, now); }

 private:
  std::string path_;
  std::FILE* warnings_;
  BusHistory earlier_;
  uint64_t saved_ = 0;  // the judging counters' sum at the last write
};

}  // namespace curio::app::host
