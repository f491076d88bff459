// The CiA 402 drive (firmware/protocol/cia402_drive.hpp): every transition of the state table
// from every state, fault reset only on the rising edge of bit 7, the statusword bits, and
// entering Fault.
#include <gtest/gtest.h>

#include "firmware/protocol/cia402_drive.hpp"

namespace od = curio::protocol::od;

using namespace curio::protocol::cia402;

namespace {

Drive in_state(DriveState s, uint16_t controlword = 0) {
  Drive d;
  d.state = s;
  d.controlword = controlword;
  return d;
}

}  // namespace

TEST(Cia402Drive, PowersOnSwitchOnDisabled) {
  const Drive d;
  EXPECT_EQ(d.state, DriveState::kSwitchOnDisabled);
  EXPECT_EQ(d.controlword, 0);
  EXPECT_EQ(d.mode, 0);
  EXPECT_EQ(d.ip_value, 10);
  EXPECT_EQ(d.ip_index, -3);
}

TEST(Cia402Drive, EveryCommandFromEveryState) {
  constexpr DriveState kStates[] = {DriveState::kSwitchOnDisabled, DriveState::kReadyToSwitchOn,
                                    DriveState::kSwitchedOn, DriveState::kOperationEnabled,
                                    DriveState::kQuickStopActive};
  constexpr uint16_t kCommands[] = {kCwDisableVoltage, kCwQuickStop, kCwShutdown, kCwSwitchOn,
                                    kCwEnableOperation};
  using S = DriveState;
  // Rows: the state before; columns: disable voltage, quick stop, shutdown, switch on, enable
  // operation. CiA 402 transitions: 2 shutdown, 3 switch on, 4 enable, 5 disable operation,
  // 6 / 8 shutdown, 7 / 9 / 10 / 12 disable voltage or quick stop, 11 quick stop, 16 enable.
  // In quick stop active the quick stop command keeps it there (the ramp goes on; it ends in
  // switch on disabled by itself, Drive::ramp_period), and with the power-on 0x605A = 2 enable
  // operation does not take it back (transition 16 is for 0x605A = 5, 6).
  const S expected[5][5] = {
      {S::kSwitchOnDisabled, S::kSwitchOnDisabled, S::kReadyToSwitchOn, S::kSwitchOnDisabled,
       S::kSwitchOnDisabled},
      {S::kSwitchOnDisabled, S::kSwitchOnDisabled, S::kReadyToSwitchOn, S::kSwitchedOn,
       S::kReadyToSwitchOn},
      {S::kSwitchOnDisabled, S::kSwitchOnDisabled, S::kReadyToSwitchOn, S::kSwitchedOn,
       S::kOperationEnabled},
      {S::kSwitchOnDisabled, S::kQuickStopActive, S::kReadyToSwitchOn, S::kSwitchedOn,
       S::kOperationEnabled},
      {S::kSwitchOnDisabled, S::kQuickStopActive, S::kQuickStopActive, S::kQuickStopActive,
       S::kQuickStopActive},
  };
  for (int s = 0; s < 5; ++s) {
    for (int c = 0; c < 5; ++c) {
      Drive d = in_state(kStates[s]);
      d.apply_controlword(kCommands[c]);
      EXPECT_EQ(d.state, expected[s][c])
          << to_string(kStates[s]) << " + controlword 0x" << std::hex << kCommands[c];
      EXPECT_EQ(d.controlword, kCommands[c]);
    }
  }
}

TEST(Cia402Drive, QuickStopActiveGoesBackToOperationEnabledOnlyWithOption5Or6) {
  for (const int16_t option : {0, 1, 2, 5, 6}) {
    Drive d = in_state(DriveState::kQuickStopActive);
    d.quick_stop_option = option;
    d.apply_controlword(kCwEnableOperation);
    EXPECT_EQ(d.state, option >= 5 ? DriveState::kOperationEnabled : DriveState::kQuickStopActive)
        << "0x605A = " << option;
  }
}

TEST(Cia402Drive, ControlwordBitsOutsideTheCommandAreDontCare) {
  // Bits 4-6 and 8-15 (operation mode specific, halt, manufacturer) do not change the command.
  Drive d;
  for (const uint16_t cw : {uint16_t{0xFF06}, uint16_t{0x0177}, uint16_t{0x7F7F}})
    d.apply_controlword(cw);
  EXPECT_EQ(d.state, DriveState::kOperationEnabled);
  d.apply_controlword(0x1070);  // disable voltage (bit 1 clear)
  EXPECT_EQ(d.state, DriveState::kSwitchOnDisabled);
}

TEST(Cia402Drive, EnableSequenceFromPowerOn) {
  Drive d;
  d.apply_controlword(kCwShutdown);
  EXPECT_EQ(d.state, DriveState::kReadyToSwitchOn);
  d.apply_controlword(kCwSwitchOn);
  EXPECT_EQ(d.state, DriveState::kSwitchedOn);
  d.apply_controlword(kCwEnableOperation);
  EXPECT_EQ(d.state, DriveState::kOperationEnabled);
}

TEST(Cia402Drive, FaultResetBitOutsideFaultChangesNothing) {
  for (const DriveState s : {DriveState::kSwitchOnDisabled, DriveState::kSwitchedOn,
                             DriveState::kOperationEnabled, DriveState::kQuickStopActive}) {
    Drive d = in_state(s);
    d.apply_controlword(kCwFaultReset | kCwDisableVoltage);
    EXPECT_EQ(d.state, s) << to_string(s);
    EXPECT_EQ(d.controlword, kCwFaultReset);
  }
}

TEST(Cia402Drive, FaultResetOnlyOnTheRisingEdgeOfBit7) {
  Drive d = in_state(DriveState::kFault);
  for (const uint16_t cw :
       {kCwDisableVoltage, kCwShutdown, kCwSwitchOn, kCwEnableOperation, kCwQuickStop}) {
    d.apply_controlword(cw);
    EXPECT_EQ(d.state, DriveState::kFault) << "controlword 0x" << std::hex << cw;
  }
  d.apply_controlword(kCwFaultReset);  // 0 → 1
  EXPECT_EQ(d.state, DriveState::kSwitchOnDisabled);

  // Bit 7 already set when the fault came: holding it does not reset; 1 → 0 → 1 does.
  d = in_state(DriveState::kFault, kCwFaultReset | kCwEnableOperation);
  d.apply_controlword(kCwFaultReset | kCwEnableOperation);
  EXPECT_EQ(d.state, DriveState::kFault);
  d.apply_controlword(kCwFaultReset);
  EXPECT_EQ(d.state, DriveState::kFault);
  d.apply_controlword(kCwEnableOperation);
  EXPECT_EQ(d.state, DriveState::kFault);
  d.apply_controlword(kCwFaultReset | kCwEnableOperation);
  EXPECT_EQ(d.state, DriveState::kSwitchOnDisabled) << "the reset edge does not also enable";
}

TEST(Cia402Drive, StatuswordOfEveryState) {
  for (const DriveState s :
       {DriveState::kSwitchOnDisabled, DriveState::kReadyToSwitchOn, DriveState::kSwitchedOn,
        DriveState::kOperationEnabled, DriveState::kQuickStopActive, DriveState::kFault}) {
    for (const int8_t mode : {int8_t{0}, kModeCyclicSynchronousPosition}) {
      Drive d = in_state(s);
      d.mode = mode;
      const uint16_t sw = d.statusword();
      EXPECT_EQ(decode_state(sw), s) << to_string(s);
      EXPECT_NE(sw & kSwRemote, 0) << to_string(s);
      const bool follows =
          s == DriveState::kOperationEnabled && mode == kModeCyclicSynchronousPosition;
      EXPECT_EQ(d.follows_target(), follows) << to_string(s) << " mode " << int{mode};
      EXPECT_EQ((sw & kSwFollowingTarget) != 0, follows) << to_string(s);
      EXPECT_EQ((sw & kSwTargetReached) != 0, follows) << to_string(s);
    }
  }
  Drive d = in_state(DriveState::kOperationEnabled);
  d.mode = kModeCyclicSynchronousPosition;
  EXPECT_EQ(d.statusword(), 0x1627);
  d.mode = 0;
  EXPECT_EQ(d.statusword(), 0x0227);
  EXPECT_EQ(in_state(DriveState::kFault).statusword(), 0x0208);
  EXPECT_EQ(Drive{}.statusword(), 0x0240);
}

TEST(Cia402Drive, RaiseFaultOnceFromAnyState) {
  // A drive that moves the joint (operation enabled, quick stop active) first runs its fault
  // reaction (0x605E = 2: the quick stop ramp); the others are in Fault at once, as every
  // drive is with 0x605E = 0.
  for (const int16_t reaction : {od::kFaultReactionDisableDrive, od::kFaultReactionQuickStopRamp}) {
    for (const DriveState s :
         {DriveState::kSwitchOnDisabled, DriveState::kReadyToSwitchOn, DriveState::kSwitchedOn,
          DriveState::kOperationEnabled, DriveState::kQuickStopActive}) {
      Drive d = in_state(s);
      d.fault_reaction = reaction;
      d.mode = kModeCyclicSynchronousPosition;
      EXPECT_TRUE(d.raise_fault()) << to_string(s);
      const bool moving = s == DriveState::kOperationEnabled || s == DriveState::kQuickStopActive;
      const DriveState first = moving && reaction != od::kFaultReactionDisableDrive
                                   ? DriveState::kFaultReactionActive
                                   : DriveState::kFault;
      EXPECT_EQ(d.state, first) << to_string(s);
      EXPECT_FALSE(d.follows_target());
      EXPECT_FALSE(d.raise_fault()) << "in Fault or its reaction already: no second EMCY";
      EXPECT_TRUE(d.ramp_period(MotionLimits{}) || first == DriveState::kFault)
          << "at rest: standstill in the first period";
      EXPECT_EQ(d.state, DriveState::kFault);
      EXPECT_EQ(decode_state(d.statusword()), DriveState::kFault);
    }
  }
}

TEST(Cia402Drive, FaultReactionActiveIgnoresCommandsAndEndsInFault) {
  Drive d = in_state(DriveState::kOperationEnabled);
  d.motion.velocity_counts_s = 2'000'000;
  d.quick_stop_deceleration = 100'000'000;  // 20 ms to standstill
  ASSERT_TRUE(d.raise_fault());
  EXPECT_EQ(decode_state(d.statusword()), DriveState::kFaultReactionActive);
  d.apply_controlword(kCwEnableOperation);
  d.apply_controlword(kCwFaultReset);
  EXPECT_EQ(d.state, DriveState::kFaultReactionActive);
  MotionLimits l;
  l.deceleration = d.quick_stop_deceleration;
  EXPECT_FALSE(d.ramp_period(l));
  EXPECT_TRUE(d.ramp_period(l));
  EXPECT_EQ(d.state, DriveState::kFault);
  EXPECT_EQ(d.motion.demand_counts, 20'000) << "v²/2a = 0.02 rad";
}
