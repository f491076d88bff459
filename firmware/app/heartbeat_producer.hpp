// The controller's own heartbeat (CiA 301 heartbeat producer, like CANopenNode's
// CO_NMT_Heartbeat): COB-ID 0x700 + the master's node id, state operational, every period.
// Each joint consumes it (0x1016, written at bring-up, drive_config.hpp) and stops on its
// quick-stop ramp when it misses it: a controller that dies, hangs or loses the bus stops the
// arm. It is produced from the master's pump, which wakes at least every 10 ms whatever it
// waits for; a controller that stops running its loop stops producing it, which is the point.
// Heartbeat frames are counted apart (heartbeats_sent): an episode's frame counts stay a
// function of the episode alone.
#pragma once
#include <cstdint>

#include "hal/can_bus.hpp"

namespace curio::app {

class HeartbeatProducer {
 public:
  // Node id 1..127 and period > 0 (ControllerConfig checks them); the first heartbeat goes
  // out at the next poll after start().
  void start(uint8_t node, uint16_t period_ms, uint64_t now);
  void stop() { active_ = false; }
  bool active() const { return active_; }
  // The next poll sends a heartbeat whatever the period says. Bring-up calls it right after it
  // configures the drives' consumers: a CiA 301 consumer watches only from the first heartbeat
  // after its configuration, so until then a controller that dies leaves the drives running.
  void due_now(uint64_t now) {
    if (active_) next_us_ = now;
  }
  // Sends the heartbeat if it is due; true when one was sent.
  bool poll(hal::CanBus& bus, uint64_t now);
  // When the next heartbeat is due (UINT64_MAX when stopped): the pump wakes up for it.
  uint64_t next_due_us() const { return active_ ? next_us_ : UINT64_MAX; }

 private:
  bool active_ = false;
  uint8_t node_ = 0;
  uint32_t period_us_ = 0;
  uint64_t next_us_ = 0;
};

}  // namespace curio::app
