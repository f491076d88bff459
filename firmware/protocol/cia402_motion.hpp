// The position demand of one CiA 402 drive in cyclic synchronous position mode, one
// interpolation period (0x60C2) at a time: the target clamped to the software position limits
// (0x607D), its step limited to the maximum velocity (the lower of 0x607F and 0x6080), the
// quick stop ramp (0x6085) that brings the joint to standstill in the drive's own time, and the
// following error monitor (0x6065 window for longer than 0x6066).
//
// Units: counts (1 count = 1 µrad), counts/s, counts/s², µs. Integer arithmetic only, so the
// simulated drive and a Cortex-M one step alike. Firmware discipline: no allocation.
#pragma once
#include <cstdint>

namespace curio::protocol::cia402 {

struct MotionLimits {
  int32_t min_counts = INT32_MIN;  // software position limits (0x607D.1/.2)
  int32_t max_counts = INT32_MAX;
  uint32_t max_velocity = UINT32_MAX;  // counts/s: min(0x607F, 0x6080)
  uint32_t deceleration = 1;           // counts/s², quick stop deceleration (0x6085), > 0
};

// `target` clamped into [min, max].
constexpr int32_t clamp_to_limits(int32_t target, const MotionLimits& l) {
  return target < l.min_counts ? l.min_counts : (target > l.max_counts ? l.max_counts : target);
}

// The largest step of the demand in one period of `period_us` at `max_velocity` (counts).
constexpr int64_t max_step_counts(uint32_t max_velocity, uint32_t period_us) {
  return static_cast<int64_t>(static_cast<uint64_t>(max_velocity) * period_us / 1'000'000u);
}

struct Motion {
  int32_t demand_counts = 0;      // position demand of the last period
  int64_t velocity_counts_s = 0;  // its velocity over the last period

  // The drive does not drive the joint (not enabled, the world reset it): the demand is where
  // the joint is, at rest.
  void hold(int32_t actual_counts) {
    demand_counts = actual_counts;
    velocity_counts_s = 0;
  }

  // One period toward `target` (already within the limits): the demand steps by at most
  // max_step_counts. True when the step was limited.
  bool follow(int32_t target, const MotionLimits& l, uint32_t period_us);

  // One period of the ramp: the velocity falls by `deceleration` (to zero within the period
  // if it is smaller), the demand moves by the period's mean velocity and stays within the
  // limits (reaching one stops the joint there). True when the joint stands still after it.
  bool ramp(const MotionLimits& l, uint32_t period_us);

  bool standstill() const { return velocity_counts_s == 0; }
};

// Following error (CiA 402, 0x6065/0x6066): |demand − actual| beyond the window for longer
// than the time out. The window kFollowingErrorOff (0xFFFFFFFF) switches it off.
class FollowingErrorMonitor {
 public:
  // One comparison at `now_us`: true once when the error has lasted longer than the time out
  // (then quiet until the joint is back within the window).
  bool check(int32_t demand, int32_t actual, uint32_t window, uint16_t time_out_ms,
             uint64_t now_us);
  bool outside() const { return outside_; }
  int64_t last_error_counts() const { return last_error_; }
  void reset() { *this = FollowingErrorMonitor{}; }

 private:
  bool outside_ = false;
  bool reported_ = false;
  uint64_t since_us_ = 0;
  int64_t last_error_ = 0;
};

}  // namespace curio::protocol::cia402
