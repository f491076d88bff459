#include "firmware/protocol/canopen.hpp"

#include "firmware/protocol/bytes.hpp"

namespace curio::protocol {
namespace {

CanFrame classic(uint32_t id, uint8_t len) {
  CanFrame f;
  f.id = id;
  f.len = len;
  return f;
}

// Classic 11-bit data frame with identifier base + node; *node gets the node id.
CodecStatus check_node_frame(const CanFrame& f, uint32_t base, uint8_t* node) {
  if (f.id <= base || f.id > base + 0x7F) return CodecStatus::kWrongId;
  if (f.extended() || f.fd() || f.remote() || f.error()) return CodecStatus::kBadFormat;
  *node = static_cast<uint8_t>(f.id - base);
  return is_curio_node(*node) ? CodecStatus::kOk : CodecStatus::kForeignNode;
}

CodecStatus check_length(const CanFrame& f, uint8_t len) {
  return f.len == len ? CodecStatus::kOk : CodecStatus::kBadLength;
}

bool valid_nmt_state(uint8_t s) {
  return s == 0x00 || s == 0x04 || s == 0x05 || s == 0x7F;
}

}  // namespace

const char* to_string(CodecStatus s) {
  switch (s) {
    case CodecStatus::kOk:
      return "ok";
    case CodecStatus::kWrongId:
      return "not this message";
    case CodecStatus::kForeignNode:
      return "node is not one of Curio's";
    case CodecStatus::kBadFormat:
      return "wrong frame format";
    case CodecStatus::kBadLength:
      return "wrong length";
    case CodecStatus::kBadCommand:
      return "unknown command";
    case CodecStatus::kUnsupported:
      return "unsupported";
    case CodecStatus::kOutOfRange:
      return "out of range";
  }
  return "?";
}

CanFrame encode_nmt(const NmtMessage& m) {
  CanFrame f = classic(kCobNmt, 2);
  f.data[0] = static_cast<uint8_t>(m.command);
  f.data[1] = m.node;
  return f;
}

CodecStatus decode_nmt(const CanFrame& f, NmtMessage* out) {
  if (f.id != kCobNmt) return CodecStatus::kWrongId;
  if (f.extended() || f.fd() || f.remote() || f.error()) return CodecStatus::kBadFormat;
  if (f.len != 2) return CodecStatus::kBadLength;
  const uint8_t c = f.data[0];
  if (c != 0x01 && c != 0x02 && c != 0x80 && c != 0x81 && c != 0x82)
    return CodecStatus::kBadCommand;
  if (f.data[1] != 0 && !is_curio_node(f.data[1])) return CodecStatus::kForeignNode;
  out->command = static_cast<NmtCommand>(c);
  out->node = f.data[1];
  return CodecStatus::kOk;
}

CanFrame encode_sync(uint8_t counter) {
  CanFrame f = classic(kCobSync, 1);
  f.data[0] = counter;
  return f;
}

CodecStatus decode_sync(const CanFrame& f, uint8_t* counter) {
  if (f.id != kCobSync) return CodecStatus::kWrongId;
  if (f.extended() || f.fd() || f.remote() || f.error()) return CodecStatus::kBadFormat;
  if (f.len > 1) return CodecStatus::kBadLength;
  const uint8_t c = f.len == 1 ? f.data[0] : 0;
  if (f.len == 1 && (c == 0 || c > kSyncCounterMax)) return CodecStatus::kOutOfRange;
  *counter = c;
  return CodecStatus::kOk;
}

CanFrame encode_heartbeat(const Heartbeat& h) {
  CanFrame f = classic(kCobHeartbeat + h.node, 1);
  f.data[0] = static_cast<uint8_t>(h.state);
  return f;
}

CodecStatus decode_heartbeat(const CanFrame& f, Heartbeat* out) {
  uint8_t node = 0;
  CodecStatus s = check_node_frame(f, kCobHeartbeat, &node);
  if (s == CodecStatus::kOk) s = check_length(f, 1);
  if (s != CodecStatus::kOk) return s;
  if (!valid_nmt_state(f.data[0] & 0x7F)) return CodecStatus::kBadCommand;
  out->node = node;
  out->state = static_cast<NmtState>(f.data[0] & 0x7F);  // bit 7: toggle (node guarding)
  return CodecStatus::kOk;
}

CodecStatus decode_producer_heartbeat(const CanFrame& f, Heartbeat* out) {
  if (f.id <= kCobHeartbeat || f.id > kCobHeartbeat + 0x7F) return CodecStatus::kWrongId;
  if (f.extended() || f.fd() || f.remote() || f.error()) return CodecStatus::kBadFormat;
  if (f.len != 1) return CodecStatus::kBadLength;
  if (!valid_nmt_state(f.data[0] & 0x7F)) return CodecStatus::kBadCommand;
  out->node = static_cast<uint8_t>(f.id - kCobHeartbeat);
  out->state = static_cast<NmtState>(f.data[0] & 0x7F);
  return CodecStatus::kOk;
}

CanFrame encode_emcy(const Emergency& e) {
  CanFrame f = classic(kCobEmcy + e.node, 8);
  put_le16(f.data, e.error_code);
  f.data[2] = e.error_register;
  for (int i = 0; i < 5; ++i) f.data[3 + i] = e.vendor[i];
  return f;
}

CodecStatus decode_emcy(const CanFrame& f, Emergency* out) {
  uint8_t node = 0;
  CodecStatus s = check_node_frame(f, kCobEmcy, &node);
  if (s == CodecStatus::kOk) s = check_length(f, 8);
  if (s != CodecStatus::kOk) return s;
  out->node = node;
  out->error_code = get_le16(f.data);
  out->error_register = f.data[2];
  for (int i = 0; i < 5; ++i) out->vendor[i] = f.data[3 + i];
  return CodecStatus::kOk;
}

CanFrame encode_sdo(const SdoMessage& m) {
  const bool request = m.kind == SdoKind::kDownloadRequest || m.kind == SdoKind::kUploadRequest ||
                       m.kind == SdoKind::kClientAbort;
  CanFrame f = classic((request ? kCobSdoRequest : kCobSdoResponse) + m.node, 8);
  const uint8_t size = (m.size >= 1 && m.size <= 4) ? m.size : uint8_t{4};
  const uint8_t n_unused = static_cast<uint8_t>((4 - size) << 2);
  uint8_t cmd = 0;
  uint32_t value = m.value;
  switch (m.kind) {
    case SdoKind::kDownloadRequest:
      cmd = static_cast<uint8_t>(0x23 | n_unused);
      break;
    case SdoKind::kUploadRequest:
      cmd = 0x40;
      value = 0;
      break;
    case SdoKind::kDownloadResponse:
      cmd = 0x60;
      value = 0;
      break;
    case SdoKind::kUploadResponse:
      cmd = static_cast<uint8_t>(0x43 | n_unused);
      break;
    case SdoKind::kClientAbort:
    case SdoKind::kNodeAbort:
      cmd = 0x80;
      break;
  }
  if (size < 4 && (m.kind == SdoKind::kDownloadRequest || m.kind == SdoKind::kUploadResponse)) {
    value &= (1u << (8 * size)) - 1u;  // unused bytes are zero on the wire
  }
  f.data[0] = cmd;
  put_le16(f.data + 1, m.index);
  f.data[3] = m.subindex;
  put_le32(f.data + 4, value);
  return f;
}

CodecStatus decode_sdo(const CanFrame& f, SdoMessage* out) {
  uint8_t node = 0;
  bool request = true;
  CodecStatus s = check_node_frame(f, kCobSdoRequest, &node);
  if (s == CodecStatus::kWrongId) {
    request = false;
    s = check_node_frame(f, kCobSdoResponse, &node);
  }
  if (s == CodecStatus::kOk) s = check_length(f, 8);
  if (s != CodecStatus::kOk) return s;
  const uint8_t cmd = f.data[0];
  const uint8_t cs = static_cast<uint8_t>(cmd >> 5);
  SdoMessage m;
  m.node = node;
  m.index = get_le16(f.data + 1);
  m.subindex = f.data[3];
  m.value = get_le32(f.data + 4);
  m.size = 4;
  if (cs == 4) {
    if (cmd != 0x80) return CodecStatus::kBadCommand;
    m.kind = request ? SdoKind::kClientAbort : SdoKind::kNodeAbort;
  } else if (request && cs == 1) {                            // initiate download
    if ((cmd & 0x02) == 0) return CodecStatus::kUnsupported;  // segmented
    m.kind = SdoKind::kDownloadRequest;
    if (cmd & 0x01) m.size = static_cast<uint8_t>(4 - ((cmd >> 2) & 0x03));
    if (cmd & 0x10) return CodecStatus::kBadCommand;  // reserved bit
  } else if (request && cs == 2) {                    // initiate upload
    if ((cmd & 0x1F) != 0) return CodecStatus::kBadCommand;
    m.kind = SdoKind::kUploadRequest;
    m.value = 0;
  } else if (!request && cs == 3) {  // download response
    if ((cmd & 0x1F) != 0) return CodecStatus::kBadCommand;
    m.kind = SdoKind::kDownloadResponse;
    m.value = 0;
  } else if (!request && cs == 2) {                           // upload response
    if ((cmd & 0x02) == 0) return CodecStatus::kUnsupported;  // segmented
    m.kind = SdoKind::kUploadResponse;
    if (cmd & 0x01) m.size = static_cast<uint8_t>(4 - ((cmd >> 2) & 0x03));
    if (cmd & 0x10) return CodecStatus::kBadCommand;
  } else if (cs != 7) {
    return CodecStatus::kUnsupported;  // segment and block transfers
  } else {
    return CodecStatus::kBadCommand;
  }
  if (m.size < 4) m.value &= (1u << (8 * m.size)) - 1u;
  *out = m;
  return CodecStatus::kOk;
}

}  // namespace curio::protocol
