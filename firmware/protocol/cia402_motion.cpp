#include "firmware/protocol/cia402_motion.hpp"

namespace curio::protocol::cia402 {
namespace {

constexpr int64_t kUsPerS = 1'000'000;

int64_t abs64(int64_t v) {
  return v < 0 ? -v : v;
}

}  // namespace

bool Motion::follow(int32_t target, const MotionLimits& l, uint32_t period_us) {
  const int64_t max_step = max_step_counts(l.max_velocity, period_us);
  int64_t step = static_cast<int64_t>(target) - demand_counts;
  const bool limited = step > max_step || step < -max_step;
  if (step > max_step) step = max_step;
  if (step < -max_step) step = -max_step;
  demand_counts = static_cast<int32_t>(demand_counts + step);
  velocity_counts_s = period_us > 0 ? step * kUsPerS / period_us : 0;
  return limited;
}

bool Motion::ramp(const MotionLimits& l, uint32_t period_us) {
  const int64_t v0 = velocity_counts_s;
  const int64_t dv = static_cast<int64_t>(l.deceleration) * period_us / kUsPerS;
  int64_t travel = 0;
  if (abs64(v0) <= dv || l.deceleration == 0) {
    // Standstill within this period: the distance of the rest of the ramp, v0²/2a.
    travel = l.deceleration == 0 ? 0 : v0 * abs64(v0) / (2 * static_cast<int64_t>(l.deceleration));
    velocity_counts_s = 0;
  } else {
    const int64_t v1 = v0 > 0 ? v0 - dv : v0 + dv;
    travel = (v0 + v1) * period_us / (2 * kUsPerS);
    velocity_counts_s = v1;
  }
  int64_t next = static_cast<int64_t>(demand_counts) + travel;
  if (next <= l.min_counts || next >= l.max_counts) {
    next = next <= l.min_counts ? l.min_counts : l.max_counts;  // a limit stops the joint
    velocity_counts_s = 0;
  }
  demand_counts = static_cast<int32_t>(next);
  return velocity_counts_s == 0;
}

bool FollowingErrorMonitor::check(int32_t demand, int32_t actual, uint32_t window,
                                  uint16_t time_out_ms, uint64_t now_us) {
  // Revolute joints: ±π is one angle (an ODE hinge reads a target of −π as +π), so the error
  // is taken modulo one turn (2π = 6,283,185 counts), as the controller's check does.
  constexpr int64_t kTurnCounts = 6'283'185;
  last_error_ = static_cast<int64_t>(demand) - actual;
  if (last_error_ > kTurnCounts / 2) last_error_ -= kTurnCounts;
  if (last_error_ < -kTurnCounts / 2) last_error_ += kTurnCounts;
  if (window == UINT32_MAX || abs64(last_error_) <= static_cast<int64_t>(window)) {
    outside_ = false;
    reported_ = false;
    return false;
  }
  if (!outside_) {
    outside_ = true;
    since_us_ = now_us;
  }
  if (reported_ || now_us - since_us_ < time_out_ms * 1000ull) return false;
  reported_ = true;
  return true;
}

}  // namespace curio::protocol::cia402
