// The wall-clock control periods (host_tools/controller/wall_clock_pacer.hpp): period t starts
// no earlier than the episode's first period + t·period, an episode's first period starts its
// own schedule at once, work longer than a period is counted as an overrun, and the figures
// count every period. Only lower bounds on time are asserted (a loaded machine is only later).
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "host_tools/controller/wall_clock_pacer.hpp"

namespace curio::app::host {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

TEST(WallClockPacer, PeriodsStartAtAbsoluteDeadlinesAndEachEpisodeStartsItsOwnSchedule) {
  WallClockPacer pacer(2000, 100);
  const auto t0 = Clock::now();
  for (int t = 0; t < 10; ++t) {
    pacer.period_begin(t);
    pacer.period_end(t);
  }
  EXPECT_GE(ms_since(t0), 18.0);  // period 9 starts 9 × 2 ms after period 0
  // Between episodes (capture, encoder) the schedule pauses; the next episode's first period
  // starts at once, and its period 1 two milliseconds after that.
  std::this_thread::sleep_for(std::chrono::milliseconds(15));
  const auto t1 = Clock::now();
  pacer.period_begin(0);
  EXPECT_LT(pacer.lateness_ns().back(), 1);  // the first period opens the schedule: never late
  pacer.period_end(0);
  pacer.period_begin(1);
  EXPECT_GE(ms_since(t1), 2.0);
  pacer.period_end(1);
  const PeriodStats s = pacer.stats();
  EXPECT_EQ(s.periods, 12);
  for (const int64_t late : pacer.lateness_ns()) EXPECT_GE(late, 0);
  EXPECT_GE(s.late_max, s.late_p99);
  EXPECT_GE(s.late_p99, s.late_p50);
}

TEST(WallClockPacer, WorkLongerThanAPeriodIsAnOverrun) {
  WallClockPacer pacer(2000, 10);
  for (int t = 0; t < 4; ++t) {
    pacer.period_begin(t);
    if (t == 1 || t == 2) std::this_thread::sleep_for(std::chrono::microseconds(4500));  // > 2 periods
    pacer.period_end(t);
  }
  const PeriodStats s = pacer.stats();
  EXPECT_EQ(s.periods, 4);
  EXPECT_GE(s.overruns, 2);
  EXPECT_GE(s.work_max, 4500.0);
  const auto j = period_stats_json(pacer, {});
  EXPECT_EQ(j.at("period_us"), 2000);
  EXPECT_EQ(j.at("periods"), 4);
  EXPECT_EQ(j.at("overruns"), s.overruns);
  EXPECT_EQ(j.at("scheduling"), "normal");
}

TEST(WallClockPacer, AnImpossibleCpuIsRefusedWithTheReason) {
  const std::string why = enable_realtime({0, 4000});
  EXPECT_EQ(why.rfind("--cpu 4000: cannot run on that CPU", 0), 0u) << why;
  EXPECT_EQ(enable_realtime({0, -1}), "");  // nothing asked, nothing done
}

}  // namespace
}  // namespace curio::app::host
