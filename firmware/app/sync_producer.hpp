// The master's SYNC producer (CiA 301, like CANopenNode's CO_SYNC): the SYNC frame of each
// control period with its counter (1..240, then 1 again), sent in one batch with the period's
// RPDO1 targets by the control cycle (control_cycle.cpp) so that the drives latch all seven
// targets on the same SYNC.
#pragma once
#include <cstdint>

#include "firmware/protocol/canopen.hpp"

namespace curio::app {

class SyncProducer {
 public:
  // The next period's SYNC frame (the counter advances).
  hal::CanFrame next() {
    counter_ = static_cast<uint8_t>(counter_ >= protocol::kSyncCounterMax ? 1 : counter_ + 1);
    return protocol::encode_sync(counter_);
  }
  uint8_t counter() const { return counter_; }

 private:
  uint8_t counter_ = 0;
};

}  // namespace curio::app
