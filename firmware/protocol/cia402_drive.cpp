#include "firmware/protocol/cia402_drive.hpp"

namespace curio::protocol::cia402 {

void Drive::apply_controlword(uint16_t cw) {
  const uint16_t previous = controlword;
  controlword = cw;
  if (state == DriveState::kFault) {
    if ((cw & kCwFaultReset) != 0 && (previous & kCwFaultReset) == 0)
      state = DriveState::kSwitchOnDisabled;  // fault reset on the rising edge of bit 7
    return;
  }
  if ((cw & kCwFaultReset) != 0) return;
  const DriveState d = state;
  if ((cw & 0x82) == 0x00) {  // disable voltage
    state = DriveState::kSwitchOnDisabled;
  } else if ((cw & 0x86) == 0x02) {  // quick stop
    state = d == DriveState::kOperationEnabled ? DriveState::kQuickStopActive
                                               : DriveState::kSwitchOnDisabled;
  } else if ((cw & 0x87) == 0x06) {  // shutdown
    if (d == DriveState::kSwitchOnDisabled || d == DriveState::kReadyToSwitchOn ||
        d == DriveState::kSwitchedOn || d == DriveState::kOperationEnabled)
      state = DriveState::kReadyToSwitchOn;
  } else if ((cw & 0x8F) == 0x07) {  // switch on / disable operation
    if (d == DriveState::kReadyToSwitchOn || d == DriveState::kOperationEnabled)
      state = DriveState::kSwitchedOn;
  } else if ((cw & 0x8F) == 0x0F) {  // enable operation
    if (d == DriveState::kSwitchedOn || d == DriveState::kQuickStopActive)
      state = DriveState::kOperationEnabled;
  }
}

uint16_t Drive::statusword() const {
  auto sw = static_cast<uint16_t>(statusword_for(state) | kSwRemote);
  if (follows_target()) sw = static_cast<uint16_t>(sw | kSwFollowingTarget | kSwTargetReached);
  return sw;
}

bool Drive::follows_target() const {
  return state == DriveState::kOperationEnabled && mode == kModeCyclicSynchronousPosition;
}

bool Drive::raise_fault() {
  if (state == DriveState::kFault) return false;
  state = DriveState::kFault;
  return true;
}

}  // namespace curio::protocol::cia402
