// For the node tests: a NodeIo that keeps every frame sent and every event, with a settable
// clock, and an expedited SDO request.
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

inline SdoMessage sdo_request(SdoKind kind, uint8_t node, uint16_t index, uint8_t subindex,
                              uint32_t value = 0) {
  return SdoMessage{kind, node, index, subindex, value, 4};
}

}  // namespace curio::protocol::test
