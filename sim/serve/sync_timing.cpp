#include "sim/serve/sync_timing.hpp"

#include <algorithm>

namespace curio::sim::serve {

void SyncTiming::on_step(int step, uint64_t now_us) {
  if (step > 0 && have_previous_ && now_us >= previous_us_) {
    const uint64_t d = now_us - previous_us_;
    intervals_us_.push_back(static_cast<uint32_t>(std::min<uint64_t>(d, UINT32_MAX)));
  }
  have_previous_ = true;
  previous_us_ = now_us;
}

SyncTiming::Summary SyncTiming::summary() const {
  Summary s;
  s.period_us = period_us_;
  s.intervals = intervals_us_.size();
  if (intervals_us_.empty()) return s;
  std::vector<uint32_t> v = intervals_us_;
  std::sort(v.begin(), v.end());
  auto at = [&](double q) {
    return static_cast<double>(v[static_cast<size_t>(q * static_cast<double>(v.size() - 1))]);
  };
  s.p50_us = at(0.5);
  s.p99_us = at(0.99);
  s.max_us = v.back();
  for (const uint32_t d : v) {
    if (2 * static_cast<uint64_t>(d) > 3 * period_us_) ++s.late;
    if (2 * static_cast<uint64_t>(d) < period_us_) ++s.early;
  }
  return s;
}

}  // namespace curio::sim::serve
