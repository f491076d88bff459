// The master's NMT service: addressed commands and the wait for the nodes' heartbeats.
#include "firmware/app/nmt_master.hpp"

#include "firmware/app/canopen_master.hpp"
#include "firmware/app/heartbeat_consumer.hpp"

namespace curio::app {

using namespace protocol;

namespace {

// A heartbeat from every node since the last forget() (in `state`, unless any_state).
class NmtWait final : public Wait {
 public:
  NmtWait(const HeartbeatConsumer& h, bool any_state, NmtState state)
      : h_(h), any_state_(any_state), state_(state) {}
  bool done() const override {
    for (int i = 0; i < kArmNodes; ++i) {
      if (!h_.heard(i)) return false;
      if (!any_state_ && h_.state(i) != state_) return false;
    }
    return true;
  }

 private:
  const HeartbeatConsumer& h_;
  bool any_state_;
  NmtState state_;
};

}  // namespace

bool NmtMaster::send(NmtCommand command) {
  hal::CanFrame frames[kArmNodes];
  for (int i = 0; i < kArmNodes; ++i) {
    heartbeats_->on_nmt_sent(i);  // the node may leave operational now
    frames[i] = encode_nmt({command, node_id(i)});
  }
  return master_->send(frames, kArmNodes);
}

bool NmtMaster::await(bool any_state, NmtState state) {
  NmtWait wait(*heartbeats_, any_state, state);
  if (master_->pump_until(wait, master_->bus().now_us() + master_->config().boot_timeout_us))
    return true;
  for (int i = 0; i < kArmNodes; ++i)
    if (!heartbeats_->heard(i) || (!any_state && heartbeats_->state(i) != state))
      master_->raise(Fault::kBootTimeout, node_id(i));
  return false;
}

}  // namespace curio::app
