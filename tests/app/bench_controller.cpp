// curio-bench-controller: episodes/s and frames per episode of the controller
// driving the simulated arm over each bus, beside curio-lab's in-process rate, and the
// controller's CPU time per SYNC cycle. Prints figures; asserts nothing about speed.
//
//   curio-bench-controller [--episodes N] [--physics ode|kinematic|both] [--buses
//   loopback,udp,vcan]
//
// Bus runs use two threads of this process with separate endpoints (UDP: two sockets on
// 127.0.0.1, exactly what `curio-sim serve` and `curio-controller` do as two processes).
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "tests/app/app_test_util.hpp"
#include "hal/linux/open_bus.hpp"
#include "hal/linux/udp_bus.hpp"

namespace curio::app::test {
namespace {

uint64_t thread_cpu_ns() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<uint64_t>(ts.tv_sec) * 1'000'000'000ull + static_cast<uint64_t>(ts.tv_nsec);
}

// CPU time of the controller's thread per SYNC cycle: all of it (computing targets, encoding,
// the send and receive syscalls, decoding, checks), and the part outside the bus waits.
class CpuProbe final : public CycleProbe {
 public:
  void cycle_work_begin() override {
    begin_ = thread_cpu_ns();
    in_waits_ = 0;
  }
  void cycle_work_end() override {
    const uint64_t total = thread_cpu_ns() - begin_;
    total_.push_back(total);
    outside_waits_.push_back(total - in_waits_);
  }
  void cycle_wait_begin() override { wait_begin_ = thread_cpu_ns(); }
  void cycle_wait_end() override { in_waits_ += thread_cpu_ns() - wait_begin_; }

  static double median_us(std::vector<uint64_t> v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return static_cast<double>(v[v.size() / 2]) / 1000.0;
  }
  double median_total_us() const { return median_us(total_); }
  double median_outside_waits_us() const { return median_us(outside_waits_); }
  size_t cycles() const { return total_.size(); }

 private:
  uint64_t begin_ = 0, wait_begin_ = 0, in_waits_ = 0;
  std::vector<uint64_t> total_, outside_waits_;
};

struct Figures {
  double episodes_per_s = 0;
  double controller_frames = 0;  // sent + received by the controller, per episode
  double wire_frames = 0;        // frames put on the bus by both sides, per episode
  double cpu_cycle_us = 0, cpu_cycle_outside_us = 0;
  std::string error;
};

Figures run_bus(hal::CanBus* arm_bus, hal::CanBus* controller_bus, sim::Physics physics,
                int episodes, bool image, bool cpu) {
  Figures f;
  const lab::RunSpec spec = mge_efr_spec(physics, 0, episodes, 100);
  ArmThread arm(arm_bus, serve_options(spec));
  CpuProbe probe;
  host::BusRunOptions o;
  o.spec = spec;
  o.controller.want_image = image;
  o.probe = cpu ? &probe : nullptr;  // 4 clock syscalls per cycle: off where they are slow (UML)
  const host::BusRunResult r = host::run_over_bus(controller_bus, o);
  arm.stop();
  const double n = static_cast<double>(r.run.final_ball.size());
  if (!r.run.error.empty() || n == 0) {
    f.error = r.run.error.empty() ? "no episodes" : r.run.error;
    return f;
  }
  f.episodes_per_s = n / r.seconds;
  f.controller_frames = static_cast<double>(r.frames_sent + r.frames_received) / n;
  f.wire_frames = static_cast<double>(r.frames_sent + arm.nodes().counters().frames_out) / n;
  f.cpu_cycle_us = probe.median_total_us();
  f.cpu_cycle_outside_us = probe.median_outside_waits_us();
  return f;
}

void print(const char* bus, sim::Physics physics, bool image, const Figures& f) {
  if (!f.error.empty()) {
    std::printf("  %-9s %-9s %-5s  failed: %s\n", bus, sim::physics_name(physics),
                image ? "yes" : "no", f.error.c_str());
    return;
  }
  std::printf(
      "  %-9s %-9s %-5s  %8.0f episodes/s   %6.0f frames/episode on the wire (%4.0f at the "
      "controller)",
      bus, sim::physics_name(physics), image ? "yes" : "no", f.episodes_per_s, f.wire_frames,
      f.controller_frames);
  if (f.cpu_cycle_us > 0) {
    std::printf("   CPU/SYNC median %5.1f µs (%4.1f µs outside bus waits)", f.cpu_cycle_us,
                f.cpu_cycle_outside_us);
  }
  std::printf("\n");
  std::fflush(stdout);
}

}  // namespace
}  // namespace curio::app::test

int main(int argc, char** argv) {
  using namespace curio;
  using namespace curio::app::test;
  int episodes = 2000;
  std::string physics_arg = "both";
  std::string buses = "loopback,udp";
  bool cpu = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--episodes" && i + 1 < argc)
      episodes = std::atoi(argv[++i]);
    else if (a == "--physics" && i + 1 < argc)
      physics_arg = argv[++i];
    else if (a == "--buses" && i + 1 < argc)
      buses = argv[++i];
    else if (a == "--no-cpu")
      cpu = false;
    else {
      std::fprintf(stderr,
                   "usage: curio-bench-controller [--episodes N] [--physics ode|kinematic|both] "
                   "[--buses loopback,udp,vcan] [--no-cpu]\n");
      return 2;
    }
  }
  std::vector<sim::Physics> physics;
  if (physics_arg != "ode") physics.push_back(sim::Physics::kKinematic);
  if (physics_arg != "kinematic") physics.push_back(sim::Physics::kOde);
  episodes = std::max(5, episodes / 5 * 5);
  std::printf(
      "curio-bench-controller: MGE-EFR seed 0, 100 + %d episodes per run; controller and "
      "simulated arm in two threads, separate bus endpoints\n",
      episodes);

  std::printf("  in-process (curio-lab's run_exploration, one thread):\n");
  for (sim::Physics p : physics) {
    const lab::RunSpec spec = mge_efr_spec(p, 0, episodes, 100);
    const lab::RunResult r = lab::run_exploration(spec);
    std::printf("  %-9s %-9s %-5s  %8.0f episodes/s\n", "in-proc", sim::physics_name(p), "-",
                (spec.explorer.n_bootstrap + spec.explorer.n_episodes) / r.seconds);
  }
  std::printf("  bus       physics   image\n");
  for (sim::Physics p : physics) {
    for (bool image : {false, true}) {
      if (buses.find("loopback") != std::string::npos) {
        auto wire = hal::LoopbackBus::create();
        auto a = wire->open();
        auto c = wire->open();
        print("loopback", p, image, run_bus(a.get(), c.get(), p, episodes, image, cpu));
      }
      if (buses.find("udp") != std::string::npos) {
        const uint16_t base = free_udp_base(hal::kUdpDefaultPorts);
        std::string error;
        auto a = hal::UdpBus::open(base, hal::kUdpDefaultPorts, &error);
        auto c = a ? hal::UdpBus::open(base, hal::kUdpDefaultPorts, &error) : nullptr;
        if (!c) {
          std::printf("  udp: cannot open: %s\n", error.c_str());
        } else {
          print("udp", p, image, run_bus(a.get(), c.get(), p, episodes, image, cpu));
        }
      }
      if (buses.find("vcan") != std::string::npos) {
        std::string error;
        auto a = hal::open_bus("socketcan:vcan0", &error);
        auto c = a ? hal::open_bus("socketcan:vcan0", &error) : nullptr;
        if (!c) {
          std::printf("  vcan: skipped (%s)\n", error.c_str());
        } else {
          print("vcan", p, image, run_bus(a.get(), c.get(), p, episodes, image, cpu));
        }
      }
    }
  }
  return 0;
}
