// The node side of CANopen (CiA 301) for Curio's simulated nodes: the NMT state machine with
// its boot-up message and heartbeat producer (0x1017), the expedited SDO server's answer, and
// NodeIo, through which a node sends, counts and reads the time (the owner of the nodes: the
// simulator on its bus, the in-image fake arm on its queue).
#pragma once
#include <cstdint>

#include "firmware/protocol/canopen.hpp"
#include "firmware/protocol/heartbeat_consumer.hpp"

namespace curio::protocol {

class NodeIo {
 public:
  enum class Event : uint8_t {
    kHeartbeatSent,  // boot-up messages included
    kEmcySent,
    kTargetRejected,   // a joint target beyond its software position limits (clamped)
    kCaptureTaken,     // a capture request for the current episode
    kCaptureStale,     // a capture request for another episode (ignored)
    kSdoRequest,       // an SDO request a node answers
    kSdoAbort,         // of which answered with an abort
    kSdoIgnored,       // an SDO request for no node here, or a stopped or booting one
    kHeartbeatMissed,  // the consumed heartbeat (0x1016) was missed
    kTargetLimited,    // a joint target step beyond the maximum velocity (limited)
    kFollowingError,   // a joint left its following error window for too long
  };
  virtual void send(const CanFrame& f) = 0;
  virtual void count(Event e) = 0;
  virtual uint64_t now_us() = 0;

 protected:
  ~NodeIo() = default;  // not owned through this interface
};

// Which reset an NMT command made: the owner resets its part (application data) too.
enum class NmtReset : uint8_t { kNone, kCommunication, kApplication };

// CiA 301 identity (0x1000, 0x1018), read-only.
struct NodeIdentity {
  uint32_t device_type = 0;
  uint32_t vendor_id = 0;
  uint32_t product_code = 0;
  uint32_t revision = 0;
  uint32_t serial = 0;
};

struct CanopenNode {
  uint8_t id = 0;
  NmtState nmt = NmtState::kBootUp;
  uint16_t heartbeat_ms = 0;  // heartbeat producer time (0x1017), 0 = off
  uint64_t next_heartbeat_us = 0;
  NodeIdentity identity;
  HeartbeatConsumer consumer;  // 0x1016.1

  // Boot-up message when leaving boot-up for pre-operational (whatever the heartbeat
  // configuration), and a heartbeat at once on a change, so a master sees it without
  // waiting a period.
  void set_nmt(NmtState state, NodeIo* io);

  // Start, stop, enter pre-operational; the resets lose the configuration (heartbeat off)
  // and boot again into pre-operational.
  NmtReset on_nmt(NmtCommand command, NodeIo* io);

  // Sends the heartbeat if it is due at `now`.
  void heartbeat_due(uint64_t now, NodeIo* io);

  // When the next heartbeat is due; UINT64_MAX when none is produced.
  uint64_t next_heartbeat_due_us() const;

  // Stopped and booting nodes do not answer SDO.
  bool serves_sdo() const { return nmt != NmtState::kStopped && nmt != NmtState::kBootUp; }

  // 0x1017 (sub 0), read or written; false: abort code in m->value.
  bool sdo_heartbeat_time(SdoMessage* m, NodeIo* io);

  // The CiA 301 objects every node has: 0x1000, 0x1001 (`error_register`, the owner's), 0x1016,
  // 0x1017, 0x1018. False with *handled false: not one of them (the owner's objects); else the
  // handler's result (false: abort code in m->value).
  bool sdo_communication(SdoMessage* m, uint8_t error_register, NodeIo* io, bool* handled);

  // A heartbeat on the bus (any node): the consumer's producer (re)arms it.
  void on_heartbeat(const Heartbeat& hb, NodeIo* io) {
    consumer.on_heartbeat(hb.node, io->now_us());
  }

  // The consumer's check at `now`: on a miss sends EMCY 0x8130 with `error_register` (the
  // communication bit added) and returns true (the owner reacts). A node in boot-up does not
  // watch.
  bool consumer_due(uint64_t now, uint8_t error_register, NodeIo* io);

  void send_heartbeat(NodeIo* io);
};

// An object handler's answers to a request (m->kind: upload or download): the value read,
// or an abort (false, code in m->value).
inline bool sdo_is_write(const SdoMessage& m) {
  return m.kind == SdoKind::kDownloadRequest;
}
inline bool sdo_value(SdoMessage* m, uint32_t value, uint8_t size) {
  m->value = value;
  m->size = size;
  return true;
}
inline bool sdo_abort(SdoMessage* m, uint32_t code) {
  m->value = code;
  return false;
}
// A read-only value: the value on upload, abort 0x06010002 on download.
inline bool sdo_read_only(SdoMessage* m, uint32_t value, uint8_t size) {
  if (sdo_is_write(*m)) return sdo_abort(m, kSdoAbortReadOnly);
  return sdo_value(m, value, size);
}

// The node's answer to an expedited request, from the copy its object handler worked on
// and the handler's result (false: abort, code in handled.value).
SdoMessage sdo_answer(const SdoMessage& request, const SdoMessage& handled, bool ok);

}  // namespace curio::protocol
