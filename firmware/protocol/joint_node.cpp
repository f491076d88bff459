#include "firmware/protocol/joint_node.hpp"

#include "firmware/protocol/arm_objects.hpp"

namespace curio::protocol {

NodeIdentity JointNode::joint_identity(uint8_t node_id) {
  NodeIdentity i;
  i.device_type = od::kDeviceTypeServoDrive;
  i.vendor_id = od::kVendorId;
  i.product_code = od::kProductCodeJoint;
  i.revision = od::kRevisionNumber;
  i.serial = od::serial_number(node_id);
  return i;
}

uint8_t JointNode::error_register() const {
  uint8_t r = 0;
  if (drive.state == cia402::DriveState::kFault ||
      drive.state == cia402::DriveState::kFaultReactionActive)
    r |= od::kErrorRegisterGeneric;
  if (consumer.missed()) r |= od::kErrorRegisterCommunication;
  return r;
}

void JointNode::ramp_check(uint64_t now) {
  const bool ramping = drive.ramping();
  if (ramping && !ramp_seen && now > last_move_us + drive.period_us())
    drive.motion.velocity_counts_s = 0;
  ramp_seen = ramping;
}

void JointNode::fault(uint16_t error_code, NodeIo* io) {
  if (!drive.raise_fault()) return;
  ramp_check(io->now_us());
  Emergency e;
  e.node = id;
  e.error_code = error_code;
  e.error_register = error_register();
  io->send(encode_emcy(e));
  io->count(NodeIo::Event::kEmcySent);
}

int32_t JointNode::clamp_target(int32_t target, NodeIo* io) {
  const cia402::MotionLimits l = limits();
  const int32_t clamped = cia402::clamp_to_limits(target, l);
  if (clamped == target) {
    clamping = false;
    return target;
  }
  io->count(NodeIo::Event::kTargetRejected);
  if (!clamping) {  // once per excursion beyond the limit
    clamping = true;
    Emergency e;
    e.node = id;
    e.error_code = od::kEmcyPositionLimit;
    e.error_register = error_register();
    io->send(encode_emcy(e));
    io->count(NodeIo::Event::kEmcySent);
  }
  return clamped;
}

void JointNode::on_command(const JointCommand& c, NodeIo* io) {
  if (nmt != NmtState::kOperational) return;
  drive.apply_controlword(c.controlword);
  ramp_check(io->now_us());
  drive.target_counts = clamp_target(c.target_counts, io);
}

double JointNode::angle_at_sync_rad(double actual_rad, NodeIo* io) {
  if (drive.ramping() || drive.state == cia402::DriveState::kQuickStopActive)
    return counts_to_angle(drive.motion.demand_counts);  // the ramp moves in ramp_period()
  if (!follows_target()) {
    int32_t actual = 0;
    if (angle_to_counts(actual_rad, &actual) == CodecStatus::kOk) drive.motion.hold(actual);
    return actual_rad;
  }
  drive_time_us += drive.period_us();
  const bool limited = drive.motion.follow(drive.target_counts, limits(), drive.period_us());
  if (io != nullptr) {
    last_move_us = io->now_us();
    if (limited) io->count(NodeIo::Event::kTargetLimited);
  }
  return counts_to_angle(drive.motion.demand_counts);
}

double JointNode::ramp_period(bool* stood_still) {
  drive_time_us += drive.period_us();
  *stood_still = drive.ramp_period(limits());
  ramp_seen = drive.ramping();
  return counts_to_angle(drive.motion.demand_counts);
}

void JointNode::after_step(int32_t actual_counts, NodeIo* io) {
  if (!follows_target() && !drive.ramping()) {
    following_error.reset();
    return;
  }
  if (following_error.check(drive.motion.demand_counts, actual_counts, drive.following_error_window,
                            drive.following_error_time_out_ms, drive_time_us)) {
    io->count(NodeIo::Event::kFollowingError);
    fault(od::kEmcyFollowingError, io);
  }
}

bool JointNode::consumer_due(uint64_t now, NodeIo* io) {
  if (!CanopenNode::consumer_due(now, error_register(), io)) return false;
  react_to_lost_connection();
  ramp_check(now);
  return true;
}

void JointNode::react_to_lost_connection() {
  switch (drive.abort_connection) {
    case od::kAbortConnectionFault:
      drive.raise_fault();  // the EMCY was 0x8130
      break;
    case od::kAbortConnectionDisableVoltage:
      if (drive.state != cia402::DriveState::kFault &&
          drive.state != cia402::DriveState::kFaultReactionActive)
        drive.state = cia402::DriveState::kSwitchOnDisabled;
      break;
    case od::kAbortConnectionQuickStop:
      drive.quick_stop();
      break;
    default:
      break;
  }
}

bool JointNode::sdo_drive_object(SdoMessage* m, bool* handled) {
  *handled = true;
  const bool write = sdo_is_write(*m);
  const uint8_t sub = m->subindex;
  const auto i16 = static_cast<int16_t>(m->value & 0xFFFF);
  auto sub0 = [&]() { return sub == 0; };
  switch (m->index) {
    case od::kAbortConnectionOption:
      if (!sub0()) return sdo_abort(m, kSdoAbortNoSubindex);
      if (!write) return sdo_value(m, static_cast<uint16_t>(drive.abort_connection), 2);
      if (i16 < od::kAbortConnectionNone || i16 > od::kAbortConnectionQuickStop)
        return sdo_abort(m, kSdoAbortValueRange);
      drive.abort_connection = i16;
      return true;
    case od::kQuickStopOptionCode:
      if (!sub0()) return sdo_abort(m, kSdoAbortNoSubindex);
      if (!write) return sdo_value(m, static_cast<uint16_t>(drive.quick_stop_option), 2);
      if (i16 != od::kQuickStopDisableDrive && i16 != od::kQuickStopSlowDownRamp &&
          i16 != od::kQuickStopRampThenDisabled && i16 != od::kQuickStopSlowDownRampStay &&
          i16 != od::kQuickStopRampStay)
        return sdo_abort(m, kSdoAbortValueRange);
      drive.quick_stop_option = i16;
      return true;
    case od::kFaultReactionOptionCode:
      if (!sub0()) return sdo_abort(m, kSdoAbortNoSubindex);
      if (!write) return sdo_value(m, static_cast<uint16_t>(drive.fault_reaction), 2);
      if (i16 < od::kFaultReactionDisableDrive || i16 > od::kFaultReactionQuickStopRamp)
        return sdo_abort(m, kSdoAbortValueRange);
      drive.fault_reaction = i16;
      return true;
    case od::kFollowingErrorWindow:
      if (!sub0()) return sdo_abort(m, kSdoAbortNoSubindex);
      if (!write) return sdo_value(m, drive.following_error_window, 4);
      drive.following_error_window = m->value;
      return true;
    case od::kFollowingErrorTimeOut:
      if (!sub0()) return sdo_abort(m, kSdoAbortNoSubindex);
      if (!write) return sdo_value(m, drive.following_error_time_out_ms, 2);
      drive.following_error_time_out_ms = static_cast<uint16_t>(m->value & 0xFFFF);
      return true;
    case od::kSoftwarePositionLimit: {
      if (sub == 0) return sdo_read_only(m, 2, 1);
      if (sub != od::kPositionLimitMinSub && sub != od::kPositionLimitMaxSub)
        return sdo_abort(m, kSdoAbortNoSubindex);
      const bool min = sub == od::kPositionLimitMinSub;
      const cia402::MotionLimits l = limits();
      if (!write) return sdo_value(m, static_cast<uint32_t>(min ? l.min_counts : l.max_counts), 4);
      const auto v = static_cast<int32_t>(m->value);
      // Within the joint's range, and min ≤ max.
      if (!within_limit(v) || (min ? v > l.max_counts : v < l.min_counts))
        return sdo_abort(m, kSdoAbortValueRange);
      (min ? drive.position_min : drive.position_max) = v;
      return true;
    }
    case od::kMaxProfileVelocity:
    case od::kMaxMotorSpeed: {
      if (!sub0()) return sdo_abort(m, kSdoAbortNoSubindex);
      uint32_t& v =
          m->index == od::kMaxProfileVelocity ? drive.max_profile_velocity : drive.max_motor_speed;
      if (!write) return sdo_value(m, v, 4);
      if (m->value == 0) return sdo_abort(m, kSdoAbortValueRange);  // the joint could not move
      v = m->value;
      return true;
    }
    case od::kQuickStopDeceleration:
      if (!sub0()) return sdo_abort(m, kSdoAbortNoSubindex);
      if (!write) return sdo_value(m, drive.quick_stop_deceleration, 4);
      if (m->value == 0) return sdo_abort(m, kSdoAbortValueRange);  // it would never stop
      drive.quick_stop_deceleration = m->value;
      return true;
    case od::kSupportedDriveModes:
      if (!sub0()) return sdo_abort(m, kSdoAbortNoSubindex);
      return sdo_read_only(m, od::kSupportedDriveModesCsp, 4);
    default:
      *handled = false;
      return false;
  }
}

bool JointNode::sdo(SdoMessage* m, int32_t actual_counts, NodeIo* io) {
  const bool ok = sdo_object(m, actual_counts, io);
  ramp_check(io->now_us());
  return ok;
}

bool JointNode::sdo_object(SdoMessage* m, int32_t actual_counts, NodeIo* io) {
  const bool write = sdo_is_write(*m);
  bool handled = false;
  bool ok = sdo_communication(m, error_register(), io, &handled);
  if (handled) return ok;
  ok = sdo_drive_object(m, &handled);
  if (handled) return ok;
  if (m->index == cia402::kInterpolationTimePeriod) {
    if (m->subindex == 0) return sdo_read_only(m, 2, 1);
    if (m->subindex == od::kInterpolationPeriodValueSub) {
      if (!write) return sdo_value(m, drive.ip_value, 1);
      if ((m->value & 0xFF) == 0) return sdo_abort(m, kSdoAbortValueRange);
      drive.ip_value = static_cast<uint8_t>(m->value);
      return true;
    }
    if (m->subindex == od::kInterpolationPeriodIndexSub) {
      if (!write) return sdo_value(m, static_cast<uint8_t>(drive.ip_index), 1);
      const auto index = static_cast<int8_t>(m->value & 0xFF);
      if (index < -6 || index > 0) return sdo_abort(m, kSdoAbortValueRange);  // 1 µs .. 1 s
      drive.ip_index = index;
      return true;
    }
    return sdo_abort(m, kSdoAbortNoSubindex);
  }
  const bool known =
      m->index == cia402::kControlword || m->index == cia402::kStatusword ||
      m->index == cia402::kModesOfOperation || m->index == cia402::kModesOfOperationDisplay ||
      m->index == cia402::kPositionActualValue || m->index == cia402::kTargetPosition;
  if (!known) return sdo_abort(m, kSdoAbortNoObject);
  if (m->subindex != 0) return sdo_abort(m, kSdoAbortNoSubindex);
  switch (m->index) {
    case cia402::kControlword:
      if (!write) return sdo_value(m, drive.controlword, 2);
      drive.apply_controlword(static_cast<uint16_t>(m->value));
      return true;
    case cia402::kStatusword:
      return sdo_read_only(m, drive.statusword(), 2);
    case cia402::kModesOfOperation:
      if (!write) return sdo_value(m, static_cast<uint8_t>(drive.mode), 1);
      if (static_cast<int8_t>(m->value & 0xFF) != cia402::kModeCyclicSynchronousPosition)
        return sdo_abort(m, kSdoAbortValueRange);
      drive.mode = cia402::kModeCyclicSynchronousPosition;
      return true;
    case cia402::kModesOfOperationDisplay:
      return sdo_read_only(m, static_cast<uint8_t>(drive.mode), 1);
    case cia402::kPositionActualValue:
      return sdo_read_only(m, static_cast<uint32_t>(actual_counts), 4);
    default: {  // cia402::kTargetPosition
      if (!write) return sdo_value(m, static_cast<uint32_t>(drive.target_counts), 4);
      drive.target_counts = clamp_target(static_cast<int32_t>(m->value), io);
      return true;
    }
  }
}

}  // namespace curio::protocol
