// One of the arm's joints as a CANopen node (ids 1–7): a CiA 402 drive in cyclic synchronous
// position mode behind the NMT/heartbeat node, with its object dictionary (arm_objects.hpp),
// RPDO1 (controlword applied at once, target latched for the next SYNC) and TPDO1. A target
// beyond the joint's limit is never applied: it faults the drive (EMCY 0x8612) or, by SDO,
// is refused. The simulated arm and the in-image fake arm share it; each steps its own world.
#pragma once
#include <cstdint>

#include "firmware/protocol/arm_messages.hpp"
#include "firmware/protocol/canopen_node.hpp"
#include "firmware/protocol/cia402_drive.hpp"

namespace curio::protocol {

struct JointNode : CanopenNode {
  cia402::Drive drive;
  int32_t limit_counts = 0;  // targets outside [−limit, limit] are refused

  bool within_limit(int32_t counts) const {
    return counts >= -limit_counts && counts <= limit_counts;
  }

  // The joint moves to the target at the next SYNC: operational, and the drive follows.
  bool follows_target() const { return nmt == NmtState::kOperational && drive.follows_target(); }

  // The joint's angle after a SYNC: the target's when it follows, else it holds `actual_rad`.
  double angle_at_sync_rad(double actual_rad) const {
    return follows_target() ? counts_to_angle(drive.target_counts) : actual_rad;
  }

  // RPDO1, in operational only (PDOs): the controlword, then the target.
  void on_command(const JointCommand& c, NodeIo* io);

  // The drive enters Fault and sends EMCY `error_code` (error register: generic error),
  // unless it is in Fault already.
  void fault(uint16_t error_code, NodeIo* io);

  // The joint's objects; `actual_counts` is the position actual value (0x6064). False: abort
  // code in m->value.
  bool sdo(SdoMessage* m, int32_t actual_counts, NodeIo* io);

  // TPDO1: statusword and position actual value.
  CanFrame feedback(int32_t actual_counts) const {
    return encode_joint_feedback({id, drive.statusword(), actual_counts});
  }

  // NMT reset node: the drive's data back to power-on values.
  void reset_application() { drive = cia402::Drive{}; }
};

}  // namespace curio::protocol
