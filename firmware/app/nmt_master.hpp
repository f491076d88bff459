// The master's NMT service (CiA 301, like CANopenNode's CO_NMT): commands go to each of the
// arm's nodes by id, never to every node on the bus (0x00: other devices on a shared bus are
// not ours to reset or stop), and the wait until every node has answered with a heartbeat.
#pragma once
#include "firmware/protocol/canopen.hpp"

namespace curio::app {

class CanOpenMaster;
class HeartbeatConsumer;

class NmtMaster {
 public:
  NmtMaster(CanOpenMaster* master, HeartbeatConsumer* heartbeats)
      : master_(master), heartbeats_(heartbeats) {}

  // The command to each of the arm's nodes, in one batch; false (fault raised) if refused.
  bool send(protocol::NmtCommand command);
  // Until every node has sent a heartbeat since HeartbeatConsumer::forget() (any state), or
  // every node reports `state`; boot_timeout_us, then kBootTimeout for each node missing.
  bool await(bool any_state, protocol::NmtState state);

 private:
  CanOpenMaster* master_;
  HeartbeatConsumer* heartbeats_;
};

}  // namespace curio::app
