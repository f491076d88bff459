#include "firmware/protocol/canopen_node.hpp"

#include "firmware/protocol/arm_objects.hpp"

namespace curio::protocol {

void CanopenNode::send_heartbeat(NodeIo* io) {
  io->send(encode_heartbeat({id, nmt}));
  io->count(NodeIo::Event::kHeartbeatSent);
  if (heartbeat_ms > 0) next_heartbeat_us = io->now_us() + heartbeat_ms * 1000ull;
}

void CanopenNode::set_nmt(NmtState state, NodeIo* io) {
  if (state == NmtState::kPreOperational && nmt == NmtState::kBootUp) {
    io->send(encode_heartbeat({id, NmtState::kBootUp}));  // boot-up (CiA 301)
    io->count(NodeIo::Event::kHeartbeatSent);
  }
  const bool changed = nmt != state;
  nmt = state;
  if (changed && heartbeat_ms > 0) send_heartbeat(io);
}

NmtReset CanopenNode::on_nmt(NmtCommand command, NodeIo* io) {
  switch (command) {
    case NmtCommand::kStart:
      set_nmt(NmtState::kOperational, io);
      return NmtReset::kNone;
    case NmtCommand::kStop:
      set_nmt(NmtState::kStopped, io);
      return NmtReset::kNone;
    case NmtCommand::kEnterPreOperational:
      set_nmt(NmtState::kPreOperational, io);
      return NmtReset::kNone;
    case NmtCommand::kResetNode:
    case NmtCommand::kResetCommunication:
      heartbeat_ms = 0;
      consumer.reset();
      nmt = NmtState::kBootUp;
      set_nmt(NmtState::kPreOperational, io);
      return command == NmtCommand::kResetNode ? NmtReset::kApplication : NmtReset::kCommunication;
  }
  return NmtReset::kNone;
}

void CanopenNode::heartbeat_due(uint64_t now, NodeIo* io) {
  if (heartbeat_ms == 0 || nmt == NmtState::kBootUp || now < next_heartbeat_us) return;
  send_heartbeat(io);
}

uint64_t CanopenNode::next_heartbeat_due_us() const {
  return heartbeat_ms > 0 && nmt != NmtState::kBootUp ? next_heartbeat_us : UINT64_MAX;
}

bool CanopenNode::sdo_heartbeat_time(SdoMessage* m, NodeIo* io) {
  if (m->subindex != 0) return sdo_abort(m, kSdoAbortNoSubindex);
  if (!sdo_is_write(*m)) return sdo_value(m, heartbeat_ms, 2);
  heartbeat_ms = static_cast<uint16_t>(m->value);
  next_heartbeat_us = io->now_us() + heartbeat_ms * 1000ull;
  return true;
}

bool CanopenNode::sdo_communication(SdoMessage* m, uint8_t error_register, NodeIo* io,
                                    bool* handled) {
  *handled = true;
  const uint8_t sub = m->subindex;
  switch (m->index) {
    case od::kDeviceType:
      if (sub != 0) return sdo_abort(m, kSdoAbortNoSubindex);
      return sdo_read_only(m, identity.device_type, 4);
    case od::kErrorRegister:
      if (sub != 0) return sdo_abort(m, kSdoAbortNoSubindex);
      return sdo_read_only(m, error_register, 1);
    case od::kHeartbeatProducerTime:
      return sdo_heartbeat_time(m, io);
    case od::kConsumerHeartbeatTime:
      if (sub == 0) return sdo_read_only(m, od::kConsumerHeartbeatEntries, 1);
      if (sub != 1) return sdo_abort(m, kSdoAbortNoSubindex);
      if (!sdo_is_write(*m)) return sdo_value(m, consumer.entry(), 4);
      if (!consumer.configure(m->value)) return sdo_abort(m, kSdoAbortValueRange);
      return true;
    case od::kIdentity:
      switch (sub) {
        case 0:
          return sdo_read_only(m, od::kIdentityEntries, 1);
        case od::kIdentityVendorSub:
          return sdo_read_only(m, identity.vendor_id, 4);
        case od::kIdentityProductSub:
          return sdo_read_only(m, identity.product_code, 4);
        case od::kIdentityRevisionSub:
          return sdo_read_only(m, identity.revision, 4);
        case od::kIdentitySerialSub:
          return sdo_read_only(m, identity.serial, 4);
        default:
          return sdo_abort(m, kSdoAbortNoSubindex);
      }
    default:
      *handled = false;
      return false;
  }
}

bool CanopenNode::consumer_due(uint64_t now, uint8_t error_register, NodeIo* io) {
  if (nmt == NmtState::kBootUp) return false;
  if (!consumer.check(now)) return false;
  Emergency e;
  e.node = id;
  e.error_code = od::kEmcyHeartbeatLost;
  e.error_register = static_cast<uint8_t>(error_register | od::kErrorRegisterCommunication);
  e.vendor[0] = consumer.producer();  // which producer was missed
  io->send(encode_emcy(e));
  io->count(NodeIo::Event::kEmcySent);
  io->count(NodeIo::Event::kHeartbeatMissed);
  return true;
}

SdoMessage sdo_answer(const SdoMessage& request, const SdoMessage& handled, bool ok) {
  SdoMessage response;
  response.node = request.node;
  response.index = request.index;
  response.subindex = request.subindex;
  if (!ok) {
    response.kind = SdoKind::kNodeAbort;
    response.value = handled.value;
  } else if (request.kind == SdoKind::kDownloadRequest) {
    response.kind = SdoKind::kDownloadResponse;
    response.value = 0;
  } else {
    response.kind = SdoKind::kUploadResponse;
    response.value = handled.value;
    response.size = handled.size;
  }
  return response;
}

}  // namespace curio::protocol
