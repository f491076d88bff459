// CiA 402 drive profile: the objects, controlword commands and statusword states Curio's
// joint nodes use in cyclic synchronous position mode (mode 8).
#pragma once
#include <cstdint>

namespace curio::protocol::cia402 {

// Object dictionary indices.
inline constexpr uint16_t kControlword = 0x6040;
inline constexpr uint16_t kStatusword = 0x6041;
inline constexpr uint16_t kModesOfOperation = 0x6060;
inline constexpr uint16_t kModesOfOperationDisplay = 0x6061;
inline constexpr uint16_t kPositionActualValue = 0x6064;
inline constexpr uint16_t kTargetPosition = 0x607A;
inline constexpr uint16_t kInterpolationTimePeriod = 0x60C2;  // sub 1: value, sub 2: 10^x s
inline constexpr int8_t kModeCyclicSynchronousPosition = 8;

// Controlword commands (bits 0-3, 7).
inline constexpr uint16_t kCwShutdown = 0x0006;
inline constexpr uint16_t kCwSwitchOn = 0x0007;
inline constexpr uint16_t kCwEnableOperation = 0x000F;
inline constexpr uint16_t kCwDisableVoltage = 0x0000;
inline constexpr uint16_t kCwQuickStop = 0x0002;
inline constexpr uint16_t kCwFaultReset = 0x0080;

// Statusword states (CiA 402 table: mask → value).
enum class DriveState : uint8_t {
  kNotReadyToSwitchOn,   // 0x4F → 0x00
  kSwitchOnDisabled,     // 0x4F → 0x40
  kReadyToSwitchOn,      // 0x6F → 0x21
  kSwitchedOn,           // 0x6F → 0x23
  kOperationEnabled,     // 0x6F → 0x27
  kQuickStopActive,      // 0x6F → 0x07
  kFaultReactionActive,  // 0x4F → 0x0F
  kFault,                // 0x4F → 0x08
  kUnknown,              // no row matches
};

constexpr DriveState decode_state(uint16_t sw) {
  if ((sw & 0x4F) == 0x00) return DriveState::kNotReadyToSwitchOn;
  if ((sw & 0x4F) == 0x40) return DriveState::kSwitchOnDisabled;
  if ((sw & 0x6F) == 0x21) return DriveState::kReadyToSwitchOn;
  if ((sw & 0x6F) == 0x23) return DriveState::kSwitchedOn;
  if ((sw & 0x6F) == 0x27) return DriveState::kOperationEnabled;
  if ((sw & 0x6F) == 0x07) return DriveState::kQuickStopActive;
  if ((sw & 0x4F) == 0x0F) return DriveState::kFaultReactionActive;
  if ((sw & 0x4F) == 0x08) return DriveState::kFault;
  return DriveState::kUnknown;
}

// The statusword a drive reports in each state (the defined bits only), for simulated nodes.
constexpr uint16_t statusword_for(DriveState s) {
  switch (s) {
    case DriveState::kNotReadyToSwitchOn:
      return 0x0000;
    case DriveState::kSwitchOnDisabled:
      return 0x0040;
    case DriveState::kReadyToSwitchOn:
      return 0x0021;
    case DriveState::kSwitchedOn:
      return 0x0023;
    case DriveState::kOperationEnabled:
      return 0x0027;
    case DriveState::kQuickStopActive:
      return 0x0007;
    case DriveState::kFaultReactionActive:
      return 0x000F;
    case DriveState::kFault:
      return 0x0008;
    case DriveState::kUnknown:
      return 0x0000;
  }
  return 0;
}

// Statusword bit 12 in CSP mode: the drive follows the target ("target position ignored"
// when 0); bit 10 target reached; bit 9 remote.
inline constexpr uint16_t kSwRemote = 1u << 9;
inline constexpr uint16_t kSwTargetReached = 1u << 10;
inline constexpr uint16_t kSwFollowingTarget = 1u << 12;

constexpr const char* to_string(DriveState s) {
  switch (s) {
    case DriveState::kNotReadyToSwitchOn:
      return "not ready to switch on";
    case DriveState::kSwitchOnDisabled:
      return "switch on disabled";
    case DriveState::kReadyToSwitchOn:
      return "ready to switch on";
    case DriveState::kSwitchedOn:
      return "switched on";
    case DriveState::kOperationEnabled:
      return "operation enabled";
    case DriveState::kQuickStopActive:
      return "quick stop active";
    case DriveState::kFaultReactionActive:
      return "fault reaction active";
    case DriveState::kFault:
      return "fault";
    case DriveState::kUnknown:
      return "unknown";
  }
  return "?";
}

}  // namespace curio::protocol::cia402
