#include "firmware/protocol/cia402_drive.hpp"

namespace curio::protocol::cia402 {

void Drive::enter_quick_stop() {
  if (state != DriveState::kOperationEnabled) {
    state = DriveState::kSwitchOnDisabled;
    return;
  }
  if (quick_stop_option == od::kQuickStopDisableDrive) {
    state = DriveState::kSwitchOnDisabled;  // the drive function off at once, no ramp
    motion.velocity_counts_s = 0;
    return;
  }
  state = DriveState::kQuickStopActive;
  ramp_done_ = false;
}

void Drive::apply_controlword(uint16_t cw) {
  const uint16_t previous = controlword;
  controlword = cw;
  if (state == DriveState::kFault) {
    if ((cw & kCwFaultReset) != 0 && (previous & kCwFaultReset) == 0)
      state = DriveState::kSwitchOnDisabled;  // fault reset on the rising edge of bit 7
    return;
  }
  if (state == DriveState::kFaultReactionActive) return;  // it ends in Fault by itself
  if ((cw & kCwFaultReset) != 0) return;
  const DriveState d = state;
  if ((cw & 0x82) == 0x00) {  // disable voltage
    state = DriveState::kSwitchOnDisabled;
  } else if ((cw & 0x86) == 0x02) {  // quick stop
    if (d != DriveState::kQuickStopActive) enter_quick_stop();
  } else if ((cw & 0x87) == 0x06) {  // shutdown
    if (d == DriveState::kSwitchOnDisabled || d == DriveState::kReadyToSwitchOn ||
        d == DriveState::kSwitchedOn || d == DriveState::kOperationEnabled)
      state = DriveState::kReadyToSwitchOn;
  } else if ((cw & 0x8F) == 0x07) {  // switch on / disable operation
    if (d == DriveState::kReadyToSwitchOn || d == DriveState::kOperationEnabled)
      state = DriveState::kSwitchedOn;
  } else if ((cw & 0x8F) == 0x0F) {  // enable operation
    // From quick stop active only where 0x605A keeps the drive there (transition 16: options
    // 5, 6); with 1 and 2 the ramp ends in switch on disabled whatever the master sends.
    const bool stays = quick_stop_option == od::kQuickStopSlowDownRampStay ||
                       quick_stop_option == od::kQuickStopRampStay;
    if (d == DriveState::kSwitchedOn || (d == DriveState::kQuickStopActive && stays))
      state = DriveState::kOperationEnabled;
  }
}

void Drive::quick_stop() {
  if (state == DriveState::kFault || state == DriveState::kFaultReactionActive ||
      state == DriveState::kQuickStopActive)
    return;
  enter_quick_stop();
}

uint16_t Drive::statusword() const {
  auto sw = static_cast<uint16_t>(statusword_for(state) | kSwRemote);
  if (follows_target()) sw = static_cast<uint16_t>(sw | kSwFollowingTarget | kSwTargetReached);
  if (state == DriveState::kQuickStopActive && ramp_done_)
    sw = static_cast<uint16_t>(sw | kSwTargetReached);  // standstill reached (CiA 402)
  return sw;
}

bool Drive::follows_target() const {
  return state == DriveState::kOperationEnabled && mode == kModeCyclicSynchronousPosition;
}

bool Drive::raise_fault() {
  if (state == DriveState::kFault || state == DriveState::kFaultReactionActive) return false;
  const bool moving =
      state == DriveState::kOperationEnabled || state == DriveState::kQuickStopActive;
  if (fault_reaction == od::kFaultReactionDisableDrive || !moving) {
    state = DriveState::kFault;
    motion.velocity_counts_s = 0;
    return true;
  }
  state = DriveState::kFaultReactionActive;
  ramp_done_ = false;
  return true;
}

bool Drive::ramp_period(const MotionLimits& l) {
  if (!ramping()) return false;
  // 0x605E values 1, 2 and 0x605A values 1, 2, 5, 6 all ramp on 0x6085 (one deceleration).
  motion.ramp(l, period_us());
  if (!motion.standstill()) return false;
  ramp_done_ = true;
  if (state == DriveState::kFaultReactionActive) {
    state = DriveState::kFault;
  } else if (quick_stop_option == od::kQuickStopSlowDownRamp ||
             quick_stop_option == od::kQuickStopRampThenDisabled) {
    state = DriveState::kSwitchOnDisabled;
  }
  return true;
}

uint32_t Drive::period_us() const {
  if (ip_index < -6 || ip_index > 0) return 0;
  uint32_t p = ip_value;  // value × 10^index s in µs: × 10^(6 + index)
  for (int i = 0; i < 6 + ip_index; ++i) p *= 10;
  return p;
}

MotionLimits Drive::limits(int32_t range_counts) const {
  MotionLimits l;
  l.min_counts = position_min < -range_counts ? -range_counts : position_min;
  l.max_counts = position_max > range_counts ? range_counts : position_max;
  l.max_velocity = max_profile_velocity < max_motor_speed ? max_profile_velocity : max_motor_speed;
  l.deceleration = quick_stop_deceleration;
  return l;
}

}  // namespace curio::protocol::cia402
