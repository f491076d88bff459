// The heartbeat consumer of a CANopen node (CiA 301 object 0x1016, one entry): it watches one
// producer's heartbeat (Curio's drives: the controller's, 0x700 + 127 by default) and reports
// once when the producer was silent for longer than the consumer time.
//
// Entry (0x1016.1, u32): bits 16–23 the producer's node id, bits 0–15 the consumer time in ms;
// node 0 or time 0: not used (the power-on value 0). Bits 24–31 are reserved (must be 0).
// Monitoring starts with the first heartbeat of the producer after the entry was set (CiA 301:
// the consumer is armed by a received heartbeat), so a node configured before its master
// produces is not tripped by the start; after a miss it waits, disarmed, for the next one.
// Any heartbeat counts (boot-up and every NMT state): what is watched is that the producer
// is alive on the bus.
//
// Firmware discipline: no allocation; the owner passes its clock in.
#pragma once
#include <cstdint>

namespace curio::protocol {

class HeartbeatConsumer {
 public:
  // Whether `entry` is a valid 0x1016.1 value (reserved bits zero, producer 0..127).
  static constexpr bool valid_entry(uint32_t entry) {
    return (entry >> 24) == 0 && ((entry >> 16) & 0xFF) <= 0x7F;
  }

  // Sets the entry (disarms); false, nothing changed, when it is not valid.
  bool configure(uint32_t entry);
  uint32_t entry() const { return (static_cast<uint32_t>(producer_) << 16) | time_ms_; }
  // The entry is in use: a producer and a time.
  bool active() const { return producer_ != 0 && time_ms_ != 0; }
  uint8_t producer() const { return producer_; }
  uint16_t time_ms() const { return time_ms_; }

  // A heartbeat of node `node` arrived at `now_us`: (re)arms when it is the producer.
  // True when it is the producer's.
  bool on_heartbeat(uint8_t node, uint64_t now_us);

  // True exactly once per silence: armed, and no heartbeat for more than the consumer time
  // at `now_us`. Then disarmed and missed() until the producer's next heartbeat.
  bool check(uint64_t now_us);

  // When check() would report the miss (the owner's next wake-up); UINT64_MAX when disarmed.
  uint64_t deadline_us() const;

  bool armed() const { return armed_; }
  // A miss was reported and no heartbeat has come since (error register bit 4).
  bool missed() const { return missed_; }
  uint64_t last_heartbeat_us() const { return last_us_; }

  // NMT reset communication: the entry back to its power-on value (off).
  void reset() { *this = HeartbeatConsumer{}; }

 private:
  uint8_t producer_ = 0;
  uint16_t time_ms_ = 0;
  bool armed_ = false;
  bool missed_ = false;
  uint64_t last_us_ = 0;
};

}  // namespace curio::protocol
