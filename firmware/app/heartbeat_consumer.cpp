// The master's heartbeat consumer.
#include "firmware/app/heartbeat_consumer.hpp"

#include "firmware/app/canopen_master.hpp"

namespace curio::app {

using namespace protocol;

void HeartbeatConsumer::on_heartbeat(const Heartbeat& hb, uint64_t now) {
  const int i = node_index(hb.node);
  if (i < 0) return;
  ControllerCounters& counters = master_->counters();
  if (hb.state == NmtState::kBootUp && !boot_up_expected_) ++counters.node_reboots;
  last_us_[i] = now;
  state_[i] = hb.state;
  heard_[i] = true;
  if (hb.state == NmtState::kOperational) {
    operational_since_nmt_[i] = true;
  } else if (operational_since_nmt_[i]) {
    // Pre-operational, stopped or a boot-up after operational: the node was not told to
    // leave (our NMT commands clear operational_since_nmt_), so it left on an error, restarted,
    // or a second node with this id answers (its heartbeat from before our command, or its
    // boot-up after our reset, comes late).
    operational_since_nmt_[i] = false;
    ++counters.state_regressions;
    counters.last_regression_node = hb.node;
  }
  if (watch_ && hb.state != NmtState::kOperational) master_->raise(Fault::kNodeState, hb.node);
}

void HeartbeatConsumer::check(uint64_t now) {
  if (!watch_) return;
  for (int i = 0; i < kArmNodes; ++i) {
    if (!master_->node_on_bus(i)) continue;
    if (now > last_us_[i] + master_->config().heartbeat_timeout_us) {
      master_->raise(Fault::kHeartbeatLost, node_id(i));
      return;
    }
  }
}

void HeartbeatConsumer::forget() {
  for (bool& h : heard_) h = false;
}

void HeartbeatConsumer::start_watch(uint64_t now) {
  for (uint64_t& t : last_us_) t = now;
  watch_ = true;
}

void HeartbeatConsumer::stop_watch() {
  watch_ = false;
}

}  // namespace curio::app
