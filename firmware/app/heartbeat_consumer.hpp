// The master's heartbeat consumer (CiA 301, like CANopenNode's CO_HBconsumer): each node's
// last heartbeat and NMT state, a node lost after heartbeat_timeout_us of silence, a node not
// operational while the arm runs, and a node's unexplained state regressions (a restart, or a
// second node with the same id).
#pragma once
#include <cstdint>

#include "firmware/app/sdo_client.hpp"
#include "firmware/protocol/canopen.hpp"

namespace curio::app {

class CanOpenMaster;

class HeartbeatConsumer {
 public:
  explicit HeartbeatConsumer(CanOpenMaster* master) : master_(master) {}

  // The dispatcher's heartbeat (boot-up included) from one of the arm's nodes.
  void on_heartbeat(const protocol::Heartbeat& hb, uint64_t now);
  // Raises kHeartbeatLost for a node silent too long (while watching).
  void check(uint64_t now);

  // Forget the heartbeats seen so far (before waiting for a fresh one from every node).
  void forget();
  // Boot-up heartbeats are counted as node reboots except while expected (our NMT reset, or
  // before our start).
  void expect_boot_up(bool expected) { boot_up_expected_ = expected; }
  // An NMT command of ours went to node index i: it may leave operational now.
  void on_nmt_sent(int i) { operational_since_nmt_[i] = false; }
  // From now on a silent node, or one not operational, is a fault; stop: neither is.
  void start_watch(uint64_t now);
  void stop_watch();
  bool watching() const { return watch_; }

  bool heard(int i) const { return heard_[i]; }
  protocol::NmtState state(int i) const { return state_[i]; }

 private:
  CanOpenMaster* master_;
  uint64_t last_us_[kArmNodes] = {};
  protocol::NmtState state_[kArmNodes] = {};
  bool heard_[kArmNodes] = {};                  // a heartbeat/boot-up since forget()
  bool operational_since_nmt_[kArmNodes] = {};  // an operational heartbeat since our last NMT
  bool watch_ = false;
  bool boot_up_expected_ = false;
};

}  // namespace curio::app
