// The master's EMCY consumer.
#include "firmware/app/emcy_consumer.hpp"

#include "firmware/app/canopen_master.hpp"

namespace curio::app {

void EmcyConsumer::on_emcy(const protocol::Emergency& e) {
  if (e.error_code == 0) return;  // "error reset / no error"
  ControllerCounters& c = master_->counters();
  ++c.emergencies;
  c.last_emcy_code = e.error_code;
  c.last_emcy_node = e.node;
  // A drive that lost an earlier master's heartbeat (it stopped on its own, as it should) is
  // brought back by this bring-up, which configures its consumer afresh: counted, no fault.
  if (e.error_code == kEmcyHeartbeatError && !master_->drives_watch_us()) return;
  master_->raise(fault_of_emcy(e.error_code), e.node);
}

}  // namespace curio::app
