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
  NmtWait(const CanOpenMaster& m, const HeartbeatConsumer& h, bool any_state, NmtState state)
      : m_(m), h_(h), any_state_(any_state), state_(state) {}
  bool done() const override {
    for (int i = 0; i < kArmNodes; ++i) {
      if (!m_.node_on_bus(i)) continue;
      if (!h_.heard(i)) return false;
      if (!any_state_ && h_.state(i) != state_) return false;
    }
    return true;
  }

 private:
  const CanOpenMaster& m_;
  const HeartbeatConsumer& h_;
  bool any_state_;
  NmtState state_;
};

}  // namespace

bool NmtMaster::send(NmtCommand command) {
  hal::CanFrame frames[kArmNodes];
  size_t n = 0;
  for (int i = 0; i < kArmNodes; ++i) {
    if (!master_->node_on_bus(i)) continue;
    heartbeats_->on_nmt_sent(i);  // the node may leave operational now
    frames[n++] = encode_nmt({command, node_id(i)});
  }
  return master_->send(frames, n);
}

bool NmtMaster::await(bool any_state, NmtState state) {
  NmtWait wait(*master_, *heartbeats_, any_state, state);
  if (master_->pump_until(wait, master_->bus().now_us() + master_->config().boot_timeout_us))
    return true;
  for (int i = 0; i < kArmNodes; ++i)
    if (master_->node_on_bus(i) &&
        (!heartbeats_->heard(i) || (!any_state && heartbeats_->state(i) != state)))
      master_->raise(Fault::kBootTimeout, node_id(i));
  return false;
}

}  // namespace curio::app
