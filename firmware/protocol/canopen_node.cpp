#include "firmware/protocol/canopen_node.hpp"

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
  if (m->subindex != 0) return sdo_abort(m, kSdoAbortNoObject);
  if (!sdo_is_write(*m)) return sdo_value(m, heartbeat_ms, 2);
  heartbeat_ms = static_cast<uint16_t>(m->value);
  next_heartbeat_us = io->now_us() + heartbeat_ms * 1000ull;
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
