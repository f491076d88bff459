// The control periods on the wall clock, as a real arm runs them (curio-controller --period-us):
// period t of an episode starts at an absolute deadline, start + t·period, reached with
// clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME); the first period of each episode opens a new
// schedule (an episode's capture and encoding lie between schedules, while the arm holds).
// Per period it measures how late the thread woke after its deadline and how long the period's
// work took (targets, frames, feedback), and counts an overrun when the work ends after the
// next period's deadline. Linux; the samples are stored in memory reserved up front.
//
// enable_realtime: SCHED_FIFO at a priority, mlockall(MCL_CURRENT | MCL_FUTURE), a pre-faulted
// stack and, optionally, one CPU, for the calling thread; "" or one line saying what was not
// permitted and how to permit it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "firmware/app/controller_types.hpp"

namespace curio::app::host {

struct PeriodStats {
  int64_t periods = 0;
  int64_t overruns = 0;
  // Microseconds: p50, p99, max of the lateness (wake − deadline) and of the work.
  double late_p50 = 0, late_p99 = 0, late_max = 0;
  double work_p50 = 0, work_p99 = 0, work_max = 0;
};

class WallClockPacer final : public PeriodPacer {
 public:
  // period_us > 0; expected_periods reserves the sample memory (more periods still work).
  WallClockPacer(int64_t period_us, int64_t expected_periods);

  void period_begin(int t) override;
  void period_end(int t) override;

  int64_t period_us() const { return period_ns_ / 1000; }
  PeriodStats stats() const;
  const std::vector<int64_t>& lateness_ns() const { return late_ns_; }
  const std::vector<int64_t>& work_ns() const { return work_ns_; }

 private:
  int64_t period_ns_;
  int64_t start_ns_ = 0;     // this episode's schedule
  int64_t deadline_ns_ = 0;  // the current period's start
  int64_t woke_ns_ = 0;
  int64_t overruns_ = 0;
  std::vector<int64_t> late_ns_, work_ns_;
};

// What a run's settings were, for summary.json.
struct RealtimeSettings {
  int priority = 0;  // 0: not asked (normal scheduling)
  int cpu = -1;      // -1: any
};
std::string enable_realtime(const RealtimeSettings& settings);

// summary.json's "control_periods" block.
nlohmann::json period_stats_json(const WallClockPacer& pacer, const RealtimeSettings& realtime);
// <dir>/control_periods.csv (one row per period) and control_periods.png (histograms of the
// lateness and the work, log counts) through gnuplot; "" or why not (gnuplot missing is
// reported as such by the caller's warning).
std::string write_period_files(const WallClockPacer& pacer, const std::string& dir, bool* gnuplot_missing);

}  // namespace curio::app::host
