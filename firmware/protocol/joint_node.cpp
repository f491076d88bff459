#include "firmware/protocol/joint_node.hpp"

#include "firmware/protocol/arm_objects.hpp"

namespace curio::protocol {

namespace {
constexpr uint8_t kErrorRegisterGeneric = 0x01;  // object 0x1001 bit 0
}  // namespace

void JointNode::fault(uint16_t error_code, NodeIo* io) {
  if (!drive.raise_fault()) return;
  Emergency e;
  e.node = id;
  e.error_code = error_code;
  e.error_register = kErrorRegisterGeneric;
  io->send(encode_emcy(e));
  io->count(NodeIo::Event::kEmcySent);
}

void JointNode::on_command(const JointCommand& c, NodeIo* io) {
  if (nmt != NmtState::kOperational) return;
  drive.apply_controlword(c.controlword);
  if (!within_limit(c.target_counts)) {
    io->count(NodeIo::Event::kTargetRejected);
    fault(od::kEmcyPositionLimit, io);
    return;
  }
  drive.target_counts = c.target_counts;
}

bool JointNode::sdo(SdoMessage* m, int32_t actual_counts, NodeIo* io) {
  const bool write = sdo_is_write(*m);
  if (m->index == od::kHeartbeatProducerTime) return sdo_heartbeat_time(m, io);
  if (m->index == cia402::kInterpolationTimePeriod) {
    if (m->subindex == od::kInterpolationPeriodValueSub) {
      if (!write) return sdo_value(m, drive.ip_value, 1);
      drive.ip_value = static_cast<uint8_t>(m->value);
      return true;
    }
    if (m->subindex == od::kInterpolationPeriodIndexSub) {
      if (!write) return sdo_value(m, static_cast<uint8_t>(drive.ip_index), 1);
      drive.ip_index = static_cast<int8_t>(m->value & 0xFF);
      return true;
    }
    return sdo_abort(m, kSdoAbortNoObject);
  }
  if (m->subindex != 0) return sdo_abort(m, kSdoAbortNoObject);
  switch (m->index) {
    case cia402::kControlword:
      if (!write) return sdo_value(m, drive.controlword, 2);
      drive.apply_controlword(static_cast<uint16_t>(m->value));
      return true;
    case cia402::kStatusword:
      if (write) return sdo_abort(m, kSdoAbortReadOnly);
      return sdo_value(m, drive.statusword(), 2);
    case cia402::kModesOfOperation:
      if (!write) return sdo_value(m, static_cast<uint8_t>(drive.mode), 1);
      if (static_cast<int8_t>(m->value & 0xFF) != cia402::kModeCyclicSynchronousPosition)
        return sdo_abort(m, kSdoAbortValueRange);
      drive.mode = cia402::kModeCyclicSynchronousPosition;
      return true;
    case cia402::kModesOfOperationDisplay:
      if (write) return sdo_abort(m, kSdoAbortReadOnly);
      return sdo_value(m, static_cast<uint8_t>(drive.mode), 1);
    case cia402::kPositionActualValue:
      if (write) return sdo_abort(m, kSdoAbortReadOnly);
      return sdo_value(m, static_cast<uint32_t>(actual_counts), 4);
    case cia402::kTargetPosition: {
      if (!write) return sdo_value(m, static_cast<uint32_t>(drive.target_counts), 4);
      const auto target = static_cast<int32_t>(m->value);
      if (!within_limit(target)) {
        io->count(NodeIo::Event::kTargetRejected);
        return sdo_abort(m, kSdoAbortValueRange);
      }
      drive.target_counts = target;
      return true;
    }
    default:
      return sdo_abort(m, kSdoAbortNoObject);
  }
}

}  // namespace curio::protocol
