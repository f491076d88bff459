// One CiA 402 joint drive in cyclic synchronous position mode, the drive's side of the
// profile (cia402.hpp decodes it for the master): the controlword state machine, the
// statusword it reports, whether it follows its target, and entering Fault.
#pragma once
#include <cstdint>

#include "firmware/protocol/cia402.hpp"

namespace curio::protocol::cia402 {

struct Drive {
  DriveState state = DriveState::kSwitchOnDisabled;
  uint16_t controlword = 0;   // the last one written (fault reset acts on bit 7's rising edge)
  int8_t mode = 0;            // modes of operation (0x6060): 0 until the master sets 8
  int32_t target_counts = 0;  // target position (0x607A), 1 count = 1 µrad
  uint8_t ip_value = 10;      // interpolation time period (0x60C2): value × 10^index s
  int8_t ip_index = -3;

  // The CiA 402 transitions a controlword command makes from the current state; applied
  // at once. In Fault only a rising edge of bit 7 (fault reset) acts.
  void apply_controlword(uint16_t cw);

  // The state's statusword, remote (bit 9) set; in operation enabled and CSP mode also
  // following target (bit 12) and target reached (bit 10).
  uint16_t statusword() const;

  // Operation enabled in CSP mode: the joint moves to the target at each SYNC (else holds).
  bool follows_target() const;

  // Enters Fault. False if the drive was in Fault already (no further EMCY is due).
  bool raise_fault();
};

}  // namespace curio::protocol::cia402
