// ISO 15765-2 (ISO-TP) transport over CAN FD or classic CAN: our own portable implementation
// (the kernel's isotp module is missing in UML and on MCUs). Pure state machines over frames:
// the caller moves frames to and from the bus and passes the time in; no heap, no clock.
//
// Frames (N_PCI, first payload bytes):
//   SF  0x0L [data]             L = 1..7            (CAN_DL ≤ 8)
//   SF  0x00 LL [data]          escape, LL = 8..62  (FD, CAN_DL > 8)
//   FF  0x1L LL [data]          12-bit length 8..4095
//   FF  0x10 0x00 L L L L       escape: 32-bit big-endian length > 4095
//   CF  0x2N [data]             N = sequence number, 1, 2, .. 15, 0, 1, ..
//   FC  0x3S BS STmin           S: 0 continue (CTS), 1 wait, 2 overflow
// Every frame we send is padded (kIsoTpPadding) to a valid CAN (FD) length of at least 8.
#pragma once
#include <cstddef>
#include <cstdint>

#include "hal/can_frame.hpp"

namespace curio::protocol {

using hal::CanFrame;

// One camera frame, 64 × 64 × 3 bytes: the largest message Curio moves.
inline constexpr size_t kIsoTpMaxMessage = 12288;
inline constexpr uint8_t kIsoTpPadding = 0xCC;

enum class IsoTpStatus : uint8_t {
  kIdle = 0,       // nothing in progress
  kInProgress,     // a message is partly through
  kComplete,       // receiver: message in the buffer; sender: last frame handed out
  kIgnored,        // not an ISO-TP frame of this link (other id or frame format)
  kSequenceError,  // consecutive frame out of order: message dropped
  kTruncated,      // frame shorter than its PCI says: message dropped
  kOversized,      // message larger than the buffer: overflow flow control sent
  kTimeout,        // N_Bs / N_Cr expired: message dropped
  kUnexpected,     // frame that makes no sense now (CF when idle, FC at a receiver, ...)
  kOverflowAbort,  // sender: the receiver answered OVFLW
  kWaitLimit,      // sender: more WAIT flow controls than allowed
  kBusy,           // sender: start() while a message is in progress
  kBadArgument,    // sender: empty or too long message
};

const char* to_string(IsoTpStatus s);

struct IsoTpCounters {
  uint32_t completed = 0;
  uint32_t sequence_errors = 0;
  uint32_t truncated = 0;
  uint32_t oversized = 0;
  uint32_t timeouts = 0;
  uint32_t unexpected = 0;
  uint32_t overflow_aborts = 0;
  uint32_t wait_limits = 0;
  uint32_t ignored = 0;
};

// Both ends of one ISO-TP connection are described from this node's point of view.
struct IsoTpLink {
  uint32_t tx_id = 0;               // our frames (data, or flow control when receiving)
  uint32_t rx_id = 0;               // the peer's frames
  bool extended = false;            // 29-bit ids
  bool fd = true;                   // CAN FD frames (else classic, TX_DL 8)
  uint8_t tx_dl = 64;               // FD data length of our SF/FF/CF frames (8..64, a DLC length)
  uint8_t block_size = 0;           // receiver: CFs per FC (0 = no further FC)
  uint8_t st_min = 0;               // receiver: STmin we ask for (ISO encoding, see st_min_us)
  uint32_t timeout_us = 1'000'000;  // N_Bs (sender waiting FC) and N_Cr (receiver waiting CF)
  uint8_t max_wait_frames = 16;     // sender: WAIT flow controls tolerated in a row
};

// ISO encoding of STmin → microseconds: 0x00-0x7F ms, 0xF1-0xF9 100-900 µs, reserved → 127 ms.
constexpr uint32_t st_min_us(uint8_t raw) {
  if (raw <= 0x7F) return raw * 1000u;
  if (raw >= 0xF1 && raw <= 0xF9) return (raw - 0xF0u) * 100u;
  return 127'000u;
}

// The frame type of an ISO-TP frame (upper PCI nibble), for dispatching frames of a link that
// both sends and receives: FC goes to the sender, the rest to the receiver.
enum class IsoTpFrameType : uint8_t {
  kSingle = 0,
  kFirst = 1,
  kConsecutive = 2,
  kFlowControl = 3,
  kInvalid = 0xF
};
IsoTpFrameType isotp_frame_type(const CanFrame& f);

struct IsoTpReply {
  bool valid = false;  // a frame to transmit now
  CanFrame frame;
};

class IsoTpReceiver {
 public:
  // `buffer` (caller-owned, `capacity` bytes) receives the messages; it must outlive this.
  IsoTpReceiver(const IsoTpLink& link, uint8_t* buffer, size_t capacity);

  // Feeds a frame from the bus (frames of other ids are kIgnored). May set a flow-control
  // reply. kComplete: the message is in data()/size() until the next SF/FF arrives.
  IsoTpStatus on_frame(const CanFrame& f, uint64_t now_us, IsoTpReply* reply);

  // Time passing: kTimeout once when a CF is overdue; while held, repeats WAIT; after
  // release, sends the pending CTS.
  IsoTpStatus poll(uint64_t now_us, IsoTpReply* reply);

  // While held, an incoming multi-frame message is answered with WAIT (the buffer is in use).
  void hold(bool held) { held_ = held; }

  // Another link (e.g. the bus's profile changed); drops the message in progress, keeps the
  // counters.
  void set_link(const IsoTpLink& link) {
    link_ = link;
    reset();
  }

  void reset();
  bool busy() const { return state_ != State::kIdle; }
  const uint8_t* data() const { return buffer_; }
  size_t size() const { return size_; }
  const IsoTpCounters& counters() const { return counters_; }

 private:
  enum class State : uint8_t { kIdle, kWaitHold, kReceiving };
  IsoTpStatus fail(IsoTpStatus s);
  void flow_control(uint8_t status, IsoTpReply* reply);
  IsoTpStatus on_single(const CanFrame& f);
  IsoTpStatus on_first(const CanFrame& f, uint64_t now_us, IsoTpReply* reply);
  IsoTpStatus on_consecutive(const CanFrame& f, uint64_t now_us, IsoTpReply* reply);

  IsoTpLink link_;
  uint8_t* buffer_;
  size_t capacity_;
  State state_ = State::kIdle;
  bool held_ = false;
  size_t size_ = 0;      // message length (complete or announced)
  size_t received_ = 0;  // bytes in the buffer so far
  uint8_t rx_dl_ = 8;    // CAN_DL of the sender's FF: every CF but the last has it
  uint8_t next_sn_ = 1;
  uint8_t block_left_ = 0;
  uint64_t last_us_ = 0;  // last frame sent or received, for N_Cr and WAIT repeats
  IsoTpCounters counters_;
};

class IsoTpSender {
 public:
  explicit IsoTpSender(const IsoTpLink& link);

  // Begins sending `size` bytes from `data` (caller-owned, unchanged until kComplete or an
  // error). kInProgress on success.
  IsoTpStatus start(const uint8_t* data, size_t size, uint64_t now_us);

  // The next frame to transmit at now_us, if any (reply->valid). kInProgress (maybe no frame
  // yet: waiting for FC or STmin), kComplete with the last frame, kIdle, or an error.
  IsoTpStatus poll(uint64_t now_us, IsoTpReply* out);

  // Feeds a flow-control frame from the bus (frames of other ids are kIgnored).
  IsoTpStatus on_frame(const CanFrame& f, uint64_t now_us);

  // Earliest time poll() may have work to do (STmin or a timeout).
  uint64_t next_event_us() const { return next_us_; }
  void abort();
  bool busy() const { return state_ != State::kIdle; }
  const IsoTpCounters& counters() const { return counters_; }

 private:
  enum class State : uint8_t { kIdle, kSendSingle, kSendFirst, kWaitFlowControl, kSendConsecutive };
  IsoTpStatus fail(IsoTpStatus s);
  void make_frame(const uint8_t* pci, size_t pci_len, size_t payload_len, IsoTpReply* out);

  IsoTpLink link_;
  const uint8_t* data_ = nullptr;
  size_t size_ = 0;
  size_t sent_ = 0;
  State state_ = State::kIdle;
  uint8_t sn_ = 1;
  uint8_t block_size_ = 0;
  uint8_t block_left_ = 0;
  uint8_t waits_ = 0;
  uint32_t st_min_us_ = 0;
  uint64_t next_us_ = 0;  // STmin gate (sending) or N_Bs deadline (waiting FC)
  IsoTpCounters counters_;
};

}  // namespace curio::protocol
