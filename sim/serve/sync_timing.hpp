// What the simulated drives feel of the controller's clock: the interval between consecutive
// SYNCs of an episode, against the control period the drives were told (`curio-sim serve
// --period-us P`, 10 ms in 0x60C2). A real CSP drive interpolates toward each target over its
// own period; a SYNC more than half a period late leaves it holding its last target for longer
// (late), one more than half a period early gives it two targets in one of its periods (early).
// The world itself still steps once per SYNC, so the measure never changes the results.
#pragma once
#include <cstdint>
#include <vector>

namespace curio::sim::serve {

class SyncTiming {
 public:
  explicit SyncTiming(uint64_t period_us) : period_us_(period_us) {}

  // The SYNC of `step` (0..49) of an episode arrived at `now_us`; step 0 starts the episode's
  // intervals (the pause between episodes is not a control period).
  void on_step(int step, uint64_t now_us);

  struct Summary {
    uint64_t period_us = 0;
    uint64_t intervals = 0;
    double p50_us = 0, p99_us = 0, max_us = 0;  // interval between SYNCs
    uint64_t late = 0;   // intervals > 1.5 periods
    uint64_t early = 0;  // intervals < 0.5 periods
  };
  Summary summary() const;

 private:
  uint64_t period_us_;
  bool have_previous_ = false;
  uint64_t previous_us_ = 0;
  std::vector<uint32_t> intervals_us_;
};

}  // namespace curio::sim::serve
