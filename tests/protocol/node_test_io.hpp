// A NodeIo for the node tests: keeps every frame sent and every event, and a settable clock.
#pragma once
#include <cstdint>
#include <vector>

#include "firmware/protocol/canopen_node.hpp"

namespace curio::protocol::test {

class RecordingIo final : public NodeIo {
 public:
  void send(const CanFrame& f) override { frames.push_back(f); }
  void count(Event e) override { events.push_back(e); }
  uint64_t now_us() override { return now; }

  size_t count_of(Event e) const {
    size_t n = 0;
    for (const Event x : events) n += x == e ? 1 : 0;
    return n;
  }
  void clear() {
    frames.clear();
    events.clear();
  }

  uint64_t now = 0;
  std::vector<CanFrame> frames;
  std::vector<Event> events;
};

}  // namespace curio::protocol::test
