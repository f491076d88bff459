// CANopen (CiA 301) framing for Curio's nodes: NMT, SYNC, EMCY, expedited SDO, heartbeat.
// Pure encode/decode over frames; every decoder checks the identifier, the frame format
// (classic, 11-bit, no RTR), the node id and the exact length before reading a byte.
#pragma once
#include <cstdint>

#include "hal/can_frame.hpp"

namespace curio::protocol {

using hal::CanFrame;

// Predefined connection set COB-IDs (function code base + node id).
inline constexpr uint32_t kCobNmt = 0x000;
inline constexpr uint32_t kCobSync = 0x080;
inline constexpr uint32_t kCobEmcy = 0x080;  // + node (1..127)
inline constexpr uint32_t kCobTpdo1 = 0x180;
inline constexpr uint32_t kCobRpdo1 = 0x200;
inline constexpr uint32_t kCobTpdo2 = 0x280;
inline constexpr uint32_t kCobRpdo2 = 0x300;
inline constexpr uint32_t kCobSdoResponse = 0x580;  // server → client (node's SDO TX)
inline constexpr uint32_t kCobSdoRequest = 0x600;   // client → server (node's SDO RX)
inline constexpr uint32_t kCobHeartbeat = 0x700;

// Curio's nodes: the arm's joints and the camera. Everything else on the bus is foreign.
inline constexpr uint8_t kFirstJointNode = 1;
inline constexpr uint8_t kJointNodes = 7;
inline constexpr uint8_t kCameraNode = 0x20;
constexpr bool is_joint_node(uint8_t node) {
  return node >= kFirstJointNode && node < kFirstJointNode + kJointNodes;
}
constexpr bool is_curio_node(uint8_t node) {
  return is_joint_node(node) || node == kCameraNode;
}

enum class CodecStatus : uint8_t {
  kOk = 0,
  kWrongId,      // the frame is not this message
  kForeignNode,  // right message type, but the node is not one of Curio's
  kBadFormat,    // FD, 29-bit id, remote or error frame where a classic data frame belongs
  kBadLength,    // length (DLC) differs from the message's
  kBadCommand,   // unknown NMT command, SDO command specifier or NMT state
  kUnsupported,  // valid CANopen we do not speak (segmented / block SDO)
  kOutOfRange,   // value not representable (encoders) or reserved value (decoders)
};

const char* to_string(CodecStatus s);

// ---- NMT (0x000, 2 bytes: command, node id; node 0 = all nodes)
enum class NmtCommand : uint8_t {
  kStart = 0x01,
  kStop = 0x02,
  kEnterPreOperational = 0x80,
  kResetNode = 0x81,
  kResetCommunication = 0x82,
};
struct NmtMessage {
  NmtCommand command = NmtCommand::kStart;
  uint8_t node = 0;
};
CanFrame encode_nmt(const NmtMessage& m);
// Accepts node 0 (broadcast) and Curio's nodes; others are kForeignNode.
CodecStatus decode_nmt(const CanFrame& f, NmtMessage* out);

// ---- SYNC (0x080, 1 byte: counter 1..240, CiA 301 synchronous counter overflow 240)
inline constexpr uint8_t kSyncCounterMax = 240;
CanFrame encode_sync(uint8_t counter);
// Length 0 (no counter, *counter = 0) or 1 (counter 1..240).
CodecStatus decode_sync(const CanFrame& f, uint8_t* counter);

// ---- Heartbeat (0x700 + node, 1 byte: NMT state)
enum class NmtState : uint8_t {
  kBootUp = 0x00,
  kStopped = 0x04,
  kOperational = 0x05,
  kPreOperational = 0x7F,
};
struct Heartbeat {
  uint8_t node = 0;
  NmtState state = NmtState::kBootUp;
};
CanFrame encode_heartbeat(const Heartbeat& h);
CodecStatus decode_heartbeat(const CanFrame& f, Heartbeat* out);
// A heartbeat of any node 1..127 (a producer a node consumes, such as the controller's
// 0x700 + 127, which is none of Curio's nodes); encode_heartbeat encodes any node too.
CodecStatus decode_producer_heartbeat(const CanFrame& f, Heartbeat* out);

// ---- EMCY (0x080 + node, 8 bytes: error code u16, error register u8, 5 vendor bytes)
struct Emergency {
  uint8_t node = 0;
  uint16_t error_code = 0;     // CiA 301/402 code, e.g. 0x8611 following error
  uint8_t error_register = 0;  // object 0x1001
  uint8_t vendor[5] = {};
};
CanFrame encode_emcy(const Emergency& e);
CodecStatus decode_emcy(const CanFrame& f, Emergency* out);

// ---- SDO, expedited transfers only (8 bytes: command, index u16, subindex, data u32)
enum class SdoKind : uint8_t {
  kDownloadRequest,   // client → node: write value (ccs 1, expedited)
  kUploadRequest,     // client → node: read (ccs 2)
  kDownloadResponse,  // node → client: write done (scs 3)
  kUploadResponse,    // node → client: value (scs 2, expedited)
  kClientAbort,       // client → node: abort code in value
  kNodeAbort,         // node → client: abort code in value
};
struct SdoMessage {
  SdoKind kind = SdoKind::kUploadRequest;
  uint8_t node = 0;
  uint16_t index = 0;
  uint8_t subindex = 0;
  uint32_t value = 0;  // data (little-endian on the wire) or abort code
  uint8_t size = 4;    // data bytes 1..4 for expedited transfers with data
};
// Client messages go on 0x600 + node, node messages on 0x580 + node; the kind says which.
CanFrame encode_sdo(const SdoMessage& m);
// Decodes a request (0x600+node) or response (0x580+node); segmented/block → kUnsupported.
CodecStatus decode_sdo(const CanFrame& f, SdoMessage* out);

// Common abort codes (CiA 301 7.2.4.3.17).
inline constexpr uint32_t kSdoAbortTimeout = 0x05040000;
inline constexpr uint32_t kSdoAbortBadCommand = 0x05040001;
inline constexpr uint32_t kSdoAbortNoObject = 0x06020000;
inline constexpr uint32_t kSdoAbortReadOnly = 0x06010002;
inline constexpr uint32_t kSdoAbortValueRange = 0x06090030;
inline constexpr uint32_t kSdoAbortNoSubindex = 0x06090011;  // the object exists, the sub not

}  // namespace curio::protocol
