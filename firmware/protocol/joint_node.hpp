// One of the arm's joints as a CANopen node (ids 1–7): a CiA 402 servo drive in cyclic
// synchronous position mode behind the NMT/heartbeat node, with its object dictionary
// (arm_objects.hpp), RPDO1 (controlword applied at once, target latched for the next SYNC) and
// TPDO1. The drive enforces its configuration: a target outside the software position limits
// (0x607D, within the joint range) is clamped to the limit and reported (EMCY 0x8612 once per
// excursion, counted kTargetRejected); a target step beyond the maximum velocity
// (0x607F/0x6080) per interpolation period is limited (counted kTargetLimited); a following
// error (0x6065/0x6066) sends EMCY 0x8611 and starts the fault reaction (0x605E); a missed
// heartbeat of the consumed producer (0x1016) sends EMCY 0x8130 and reacts as 0x6007 says.
// The quick stop and fault reaction ramps (0x6085) run in the drive's own time: the owner
// calls ramp_period() once per interpolation period of its clock, SYNC or not.
// The simulated arm and the in-image fake arm share it; each steps its own world.
#pragma once
#include <cstdint>

#include "firmware/protocol/arm_messages.hpp"
#include "firmware/protocol/canopen_node.hpp"
#include "firmware/protocol/cia402_drive.hpp"

namespace curio::protocol {

struct JointNode : CanopenNode {
  cia402::Drive drive;
  int32_t limit_counts = 0;  // the joint range [−limit, limit]: bounds 0x607D
  bool clamping = false;     // the last target was clamped (EMCY 0x8612 sent for it)
  cia402::FollowingErrorMonitor following_error;
  uint64_t drive_time_us = 0;  // the drive's own clock: one interpolation period per step
  uint64_t last_move_us = 0;   // the owner's clock at the last step toward a target
  bool ramp_seen = false;      // ramping at the last ramp_check()

  // The identity of a joint (0x1000, 0x1018) for node `node_id`.
  static NodeIdentity joint_identity(uint8_t node_id);

  bool within_limit(int32_t counts) const {
    return counts >= -limit_counts && counts <= limit_counts;
  }
  cia402::MotionLimits limits() const { return drive.limits(limit_counts); }

  // The joint moves to the target at the next SYNC: operational, and the drive follows.
  bool follows_target() const { return nmt == NmtState::kOperational && drive.follows_target(); }

  // The joint's angle after a SYNC: the position demand when it follows (the target, its step
  // limited to the maximum velocity) or ramps (where the ramp is; it advances in
  // ramp_period() only), else it holds `actual_rad`.
  double angle_at_sync_rad(double actual_rad, NodeIo* io = nullptr);

  // The drive runs its quick stop or fault reaction ramp: the owner calls ramp_period() each
  // interpolation period of its own clock.
  bool ramping() const { return drive.ramping(); }
  // One period of the ramp: the angle to step the world with. *stood_still: the joint came
  // to standstill in this period (the drive moved on: switch on disabled or Fault).
  double ramp_period(bool* stood_still);

  // After the world stepped (SYNC or ramp): the following error check against the position
  // actual value; a trip sends EMCY 0x8611 and starts the fault reaction (0x605E).
  void after_step(int32_t actual_counts, NodeIo* io);

  // The world moved the joint to `actual_counts` by itself (an episode's start pose): the
  // drive's demand is there, at rest.
  void hold_at(int32_t actual_counts) {
    drive.motion.hold(actual_counts);
    following_error.reset();
  }

  // The heartbeat consumer at `now`: on a miss EMCY 0x8130, then the 0x6007 reaction
  // (0 none, 1 fault with the fault reaction, 2 disable voltage, 3 quick stop as 0x605A says).
  // True when it missed now.
  bool consumer_due(uint64_t now, NodeIo* io);

  // 0x1001: bit 0 while the drive is in fault or its reaction, bit 4 after a missed heartbeat.
  uint8_t error_register() const;

  // RPDO1, in operational only (PDOs): the controlword, then the target (clamped).
  void on_command(const JointCommand& c, NodeIo* io);

  // The drive starts its fault reaction and sends EMCY `error_code` (error register:
  // generic error), unless it is in Fault or its reaction already.
  void fault(uint16_t error_code, NodeIo* io);

  // The joint's objects; `actual_counts` is the position actual value (0x6064). False: abort
  // code in m->value.
  bool sdo(SdoMessage* m, int32_t actual_counts, NodeIo* io);

  // A ramp that begins at `now` starts from the joint's velocity: that of its last step if the
  // step was within one interpolation period, else zero (a joint that got no fresh target for a
  // period holds its last one: a controller that died stopped its SYNCs, and the joint stood
  // still before its heartbeat was missed). Called wherever a ramp can begin.
  void ramp_check(uint64_t now);

  // TPDO1: statusword and position actual value.
  CanFrame feedback(int32_t actual_counts) const {
    return encode_joint_feedback({id, drive.statusword(), actual_counts});
  }

  // NMT reset node: the drive's data back to power-on values.
  void reset_application() {
    drive = cia402::Drive{};
    clamping = false;
    following_error.reset();
  }

 private:
  // The target with 0x607D applied: clamped and reported when outside.
  int32_t clamp_target(int32_t target, NodeIo* io);
  bool sdo_object(SdoMessage* m, int32_t actual_counts, NodeIo* io);
  void react_to_lost_connection();  // 0x6007
  bool sdo_drive_object(SdoMessage* m, bool* handled);
};

}  // namespace curio::protocol
