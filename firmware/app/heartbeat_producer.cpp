// The controller's own heartbeat.
#include "firmware/app/heartbeat_producer.hpp"

#include "firmware/protocol/canopen.hpp"

namespace curio::app {

void HeartbeatProducer::start(uint8_t node, uint16_t period_ms, uint64_t now) {
  node_ = node;
  period_us_ = static_cast<uint32_t>(period_ms) * 1000u;
  next_us_ = now;
  active_ = period_us_ > 0;
}

bool HeartbeatProducer::poll(hal::CanBus& bus, uint64_t now) {
  if (!active_ || now < next_us_) return false;
  // Skip the periods a long pause missed: the next heartbeat keeps the period from now.
  next_us_ = now + period_us_;
  const hal::CanFrame f = protocol::encode_heartbeat({node_, protocol::NmtState::kOperational});
  return bus.send_batch(&f, 1, now + period_us_, nullptr) == hal::CanStatus::kOk;
}

}  // namespace curio::app
