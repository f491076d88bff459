#include "host_tools/controller/wall_clock_pacer.hpp"

#include <alloca.h>
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <sstream>

#include <fmt/format.h>

#include "host_tools/common/atomic_file.hpp"
#include "host_tools/common/gnuplot.hpp"

namespace curio::app::host {
namespace {

int64_t monotonic_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

void sleep_until_ns(int64_t t) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(t / 1'000'000'000);
  ts.tv_nsec = static_cast<long>(t % 1'000'000'000);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

// The q-quantile (nearest rank) of v in microseconds; v is copied.
double quantile_us(std::vector<int64_t> v, double q) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<size_t>(std::min<double>(static_cast<double>(v.size()) - 1, q * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return static_cast<double>(v[k]) / 1000.0;
}

// Touches `bytes` of stack so that its pages are resident before the first period.
void prefault_stack(size_t bytes) {
  volatile unsigned char* p = static_cast<unsigned char*>(alloca(bytes));
  for (size_t i = 0; i < bytes; i += 4096) p[i] = 0;
}

}  // namespace

WallClockPacer::WallClockPacer(int64_t period_us, int64_t expected_periods) : period_ns_(period_us * 1000) {
  late_ns_.reserve(static_cast<size_t>(expected_periods));
  work_ns_.reserve(static_cast<size_t>(expected_periods));
}

void WallClockPacer::period_begin(int t) {
  if (t == 0) {  // the schedule opens now: this period is on time by definition
    start_ns_ = monotonic_ns();
    deadline_ns_ = start_ns_;
    woke_ns_ = start_ns_;
  } else {
    deadline_ns_ = start_ns_ + static_cast<int64_t>(t) * period_ns_;
    sleep_until_ns(deadline_ns_);
    woke_ns_ = monotonic_ns();
  }
  late_ns_.push_back(std::max<int64_t>(0, woke_ns_ - deadline_ns_));
}

void WallClockPacer::period_end(int) {
  const int64_t done = monotonic_ns();
  work_ns_.push_back(done - woke_ns_);
  if (done > deadline_ns_ + period_ns_) ++overruns_;
}

PeriodStats WallClockPacer::stats() const {
  PeriodStats s;
  s.periods = static_cast<int64_t>(work_ns_.size());
  s.overruns = overruns_;
  s.late_p50 = quantile_us(late_ns_, 0.50);
  s.late_p99 = quantile_us(late_ns_, 0.99);
  s.late_max = quantile_us(late_ns_, 1.0);
  s.work_p50 = quantile_us(work_ns_, 0.50);
  s.work_p99 = quantile_us(work_ns_, 0.99);
  s.work_max = quantile_us(work_ns_, 1.0);
  return s;
}

std::string enable_realtime(const RealtimeSettings& r) {
  if (r.cpu >= 0) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(r.cpu, &set);
    if (const int e = pthread_setaffinity_np(pthread_self(), sizeof set, &set); e != 0)
      return fmt::format("--cpu {}: cannot run on that CPU ({}); this machine's CPUs are 0..{}", r.cpu,
                         std::strerror(e), static_cast<int>(sysconf(_SC_NPROCESSORS_ONLN)) - 1);
  }
  if (r.priority <= 0) return "";
  if (mlockall(MCL_CURRENT | MCL_FUTURE) != 0)
    return fmt::format("--realtime: mlockall failed ({}): raise the locked-memory limit (ulimit -l unlimited, "
                       "or memlock in /etc/security/limits.conf) or run as root",
                       std::strerror(errno));
  sched_param p{};
  p.sched_priority = r.priority;
  if (const int e = pthread_setschedparam(pthread_self(), SCHED_FIFO, &p); e != 0)
    return fmt::format("--realtime {}: SCHED_FIFO not permitted ({}): run as root, give the program "
                       "CAP_SYS_NICE (setcap cap_sys_nice+ep), or raise the user's rtprio limit (ulimit -r, "
                       "or rtprio in /etc/security/limits.conf)",
                       r.priority, std::strerror(e));
  prefault_stack(256 * 1024);
  return "";
}

nlohmann::json period_stats_json(const WallClockPacer& pacer, const RealtimeSettings& realtime) {
  const PeriodStats s = pacer.stats();
  nlohmann::json j;
  j["period_us"] = pacer.period_us();
  j["periods"] = s.periods;
  j["overruns"] = s.overruns;
  j["lateness_us"] = {{"p50", s.late_p50}, {"p99", s.late_p99}, {"max", s.late_max}};
  j["work_us"] = {{"p50", s.work_p50}, {"p99", s.work_p99}, {"max", s.work_max}};
  j["scheduling"] = realtime.priority > 0 ? fmt::format("SCHED_FIFO {}", realtime.priority) : "normal";
  j["cpu"] = realtime.cpu;
  j["first_period_of_each_episode"] = "starts its schedule (lateness 0)";
  return j;
}

std::string write_period_files(const WallClockPacer& pacer, const std::string& dir, bool* gnuplot_missing) {
  namespace fs = std::filesystem;
  std::ostringstream csv;
  csv << "period,lateness_us,work_us\n";
  const auto& late = pacer.lateness_ns();
  const auto& work = pacer.work_ns();
  for (size_t i = 0; i < work.size() && i < late.size(); ++i)
    csv << i << ',' << fmt::format("{:.3f},{:.3f}\n", static_cast<double>(late[i]) / 1000.0,
                                   static_cast<double>(work[i]) / 1000.0);
  std::string error;
  const std::string csv_path = (fs::path(dir) / "control_periods.csv").string();
  if (!curio::host::write_file_atomically(csv_path, csv.str(), &error)) return error;
  const PeriodStats s = pacer.stats();
  const std::string png = (fs::path(dir) / "control_periods.png").string();
  const std::string script = fmt::format(
      "set terminal pngcairo size 900,420\n"
      "set output {}\n"
      "set datafile separator ','\n"
      "set multiplot layout 1,2 title 'control periods of {} us: {} periods, {} overruns'\n"
      "set logscale y\nset yrange [0.8:*]\nset style fill solid 0.6\nset ylabel 'periods'\n"
      "bw = 10.0\nbin(x) = bw * floor(x / bw) + bw / 2\n"
      "set xlabel 'woke after the deadline (us)'\n"
      "set title 'lateness: p50 {:.0f}, p99 {:.0f}, max {:.0f} us'\n"
      "plot {} using (bin($2)):(1.0) smooth frequency with boxes notitle\n"
      "set xlabel 'work of the period (us)'\n"
      "set title 'work: p50 {:.0f}, p99 {:.0f}, max {:.0f} us'\n"
      "plot {} using (bin($3)):(1.0) smooth frequency with boxes notitle\n"
      "unset multiplot\n",
      curio::host::gnuplot_quote(png), pacer.period_us(), s.periods, s.overruns, s.late_p50, s.late_p99, s.late_max,
      curio::host::gnuplot_quote(csv_path), s.work_p50, s.work_p99, s.work_max, curio::host::gnuplot_quote(csv_path));
  if (!curio::host::run_gnuplot((fs::path(dir) / "control_periods.gp").string(), script, &error, gnuplot_missing)) return error;
  return "";
}

}  // namespace curio::app::host
