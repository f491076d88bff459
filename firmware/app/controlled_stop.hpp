// The controlled stop: how every run of the controller ends, whatever ended it (the last
// episode, SIGTERM/SIGINT/SIGHUP, a drive fault, an EMCY, a following error, a lost node,
// bus-off, a full disk). In order, bounded by stop_timeout_us:
//   1. quick stop (controlword 0x0002) to every joint, by SDO (served in any NMT state but
//      stopped), so the drives decelerate on their 0x6085 ramp (0x605A);
//   2. the statuswords polled until every joint that took it stands still: quick stop active
//      with target reached, or switch on disabled (0x605A = 2 ends there), or fault;
//   3. disable voltage (controlword 0x0000) to every joint, the heartbeat consumer off
//      (0x1016.1 = 0: the controller's heartbeat stops next), NMT stop to each node.
// Faults met on the way are counted, not obeyed: the stop goes on with the joints that answer.
// Nothing is sent on a bus that is off, or that another master or arm shares (not ours to
// stop); the report says so.
#pragma once
#include <cstdint>

#include "firmware/protocol/canopen.hpp"

namespace curio::app {

class CanOpenMaster;

inline constexpr uint8_t kAllJoints = (1u << protocol::kJointNodes) - 1;

struct StopReport {
  bool sent = false;           // the sequence ran (false: `skipped` says why)
  const char* skipped = "";    // why nothing was sent
  uint8_t quick_stopped = 0;   // bit j: joint j took the quick stop
  uint8_t standstill = 0;      // bit j: joint j reported standstill (step 2)
  uint8_t disabled = 0;        // bit j: joint j took disable voltage
  uint32_t standstill_us = 0;  // from the quick stop to the last joint's standstill
  bool complete() const { return sent && standstill == kAllJoints && disabled == kAllJoints; }
};

StopReport controlled_stop(CanOpenMaster& master);

}  // namespace curio::app
