#include "firmware/protocol/heartbeat_consumer.hpp"

namespace curio::protocol {

bool HeartbeatConsumer::configure(uint32_t entry) {
  if (!valid_entry(entry)) return false;
  producer_ = static_cast<uint8_t>(entry >> 16);
  time_ms_ = static_cast<uint16_t>(entry & 0xFFFF);
  armed_ = false;
  missed_ = false;
  return true;
}

bool HeartbeatConsumer::on_heartbeat(uint8_t node, uint64_t now_us) {
  if (!active() || node != producer_) return false;
  armed_ = true;
  missed_ = false;
  last_us_ = now_us;
  return true;
}

uint64_t HeartbeatConsumer::deadline_us() const {
  return armed_ ? last_us_ + time_ms_ * 1000ull : UINT64_MAX;
}

bool HeartbeatConsumer::check(uint64_t now_us) {
  if (!armed_ || now_us <= deadline_us()) return false;
  armed_ = false;
  missed_ = true;
  return true;
}

}  // namespace curio::protocol
