// One CiA 402 joint drive in cyclic synchronous position mode, the drive's side of the
// profile (cia402.hpp decodes it for the master): the controlword state machine, the
// statusword it reports, whether it follows its target, its safety options (quick stop
// 0x605A, fault reaction 0x605E, abort connection 0x6007) with the ramp that ends a quick stop
// or a fault reaction, and the motion parameters of cia402_motion.hpp.
#pragma once
#include <cstdint>

#include "firmware/protocol/arm_objects.hpp"
#include "firmware/protocol/cia402.hpp"
#include "firmware/protocol/cia402_motion.hpp"

namespace curio::protocol::cia402 {

struct Drive {
  DriveState state = DriveState::kSwitchOnDisabled;
  uint16_t controlword = 0;   // the last one written (fault reset acts on bit 7's rising edge)
  int8_t mode = 0;            // modes of operation (0x6060): 0 until the master sets 8
  int32_t target_counts = 0;  // target position (0x607A), 1 count = 1 µrad
  uint8_t ip_value = 10;      // interpolation time period (0x60C2): value × 10^index s
  int8_t ip_index = -3;

  // Safety options and motion parameters (power-on values: arm_objects.hpp).
  int16_t abort_connection = od::kPowerOnAbortConnection;   // 0x6007
  int16_t quick_stop_option = od::kPowerOnQuickStopOption;  // 0x605A
  int16_t fault_reaction = od::kPowerOnFaultReaction;       // 0x605E
  int32_t position_min = INT32_MIN;  // 0x607D.1/.2 as written (INT32_MIN/MAX: the joint range)
  int32_t position_max = INT32_MAX;
  uint32_t max_profile_velocity = od::kPowerOnMaxVelocityCounts;               // 0x607F
  uint32_t max_motor_speed = od::kPowerOnMaxVelocityCounts;                    // 0x6080
  uint32_t quick_stop_deceleration = od::kPowerOnQuickStopDecelCounts;         // 0x6085
  uint32_t following_error_window = od::kPowerOnFollowingErrorWindow;          // 0x6065
  uint16_t following_error_time_out_ms = od::kPowerOnFollowingErrorTimeOutMs;  // 0x6066

  Motion motion;  // the position demand

  // The CiA 402 transitions a controlword command makes from the current state; applied
  // at once. In Fault and fault reaction active only a rising edge of bit 7 (fault reset)
  // acts (in Fault). Quick stop from operation enabled: quick stop active and the ramp (or,
  // with 0x605A = 0, switch on disabled at once).
  void apply_controlword(uint16_t cw);

  // The state's statusword, remote (bit 9) set; in operation enabled and CSP mode also
  // following target (bit 12) and target reached (bit 10).
  uint16_t statusword() const;

  // Operation enabled in CSP mode: the joint moves to the target at each SYNC (else holds).
  bool follows_target() const;

  // A fault: fault reaction active and the ramp (0x605E 1, 2), or Fault at once (0). False if
  // the drive was in Fault or its reaction already (no further EMCY is due).
  bool raise_fault();

  // The quick stop function (0x6007 = 3 on a lost controller): as the controlword's quick
  // stop command, without changing the last controlword.
  void quick_stop();

  // Quick stop active or fault reaction active, with the joint not yet at standstill: the
  // owner steps ramp_period() once per interpolation period of its own clock.
  bool ramping() const {
    return (state == DriveState::kQuickStopActive || state == DriveState::kFaultReactionActive) &&
           !ramp_done_;
  }
  // One period of the ramp within `l` (limits()); true when the joint came to standstill in
  // it. Then quick stop active goes on to switch on disabled (0x605A 1, 2) or stays (5, 6),
  // and fault reaction active to Fault.
  bool ramp_period(const MotionLimits& l);

  // The interpolation period in µs (0x60C2), 0 when it is not representable.
  uint32_t period_us() const;

  // The limits the motion works with; the joint range [−range, range] bounds 0x607D.
  MotionLimits limits(int32_t range_counts) const;

 private:
  void enter_quick_stop();
  bool ramp_done_ = false;
};

}  // namespace curio::protocol::cia402
