// Shared pieces of the controller tests: the simulated arm in a thread, a fault-injecting
// bus in front of it (the "misbehaving node"), the in-process reference run, archive
// comparison.
#pragma once
#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "firmware/explore/explorer.hpp"
#include "hal/can_bus.hpp"
#include "hal/host/loopback_bus.hpp"
#include "host_tools/controller/bus_run.hpp"
#include "host_tools/controller/fault_text.hpp"
#include "host_tools/experiment/simulated_run.hpp"
#include "sim/serve/arm_nodes.hpp"
#include "tests/hal/bus_test_util.hpp"

namespace curio::app::test {

// θ and outcomes of every archived episode.
struct ArchiveCopy {
  int size = 0;
  int outcome_dim = 0;
  std::vector<float> theta;    // size × 49
  std::vector<float> outcome;  // size × outcome_dim
};

inline ArchiveCopy copy_archive(const Explorer& e) {
  ArchiveCopy a;
  const Archive& ar = e.archive();
  a.size = ar.size();
  a.outcome_dim = ar.outcome_dim();
  float theta[kThetaDim];
  for (int i = 0; i < a.size; ++i) {
    ar.theta(i, theta);
    a.theta.insert(a.theta.end(), theta, theta + kThetaDim);
    for (int d = 0; d < a.outcome_dim; ++d) a.outcome.push_back(ar.outcome(i, d));
  }
  return a;
}

inline bool same_bits(float a, float b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Bit-for-bit equality; the failure message names the first mismatch.
inline ::testing::AssertionResult archives_identical(const ArchiveCopy& a, const ArchiveCopy& b) {
  if (a.size != b.size || a.outcome_dim != b.outcome_dim)
    return ::testing::AssertionFailure() << "sizes differ: " << a.size << "×" << a.outcome_dim
                                         << " vs " << b.size << "×" << b.outcome_dim;
  for (size_t i = 0; i < a.theta.size(); ++i)
    if (!same_bits(a.theta[i], b.theta[i]))
      return ::testing::AssertionFailure()
             << "θ differs at episode " << i / kThetaDim << " dim " << i % kThetaDim << ": "
             << a.theta[i] << " vs " << b.theta[i];
  for (size_t i = 0; i < a.outcome.size(); ++i)
    if (!same_bits(a.outcome[i], b.outcome[i]))
      return ::testing::AssertionFailure()
             << "outcome differs at episode " << i / static_cast<size_t>(a.outcome_dim) << " dim "
             << i % static_cast<size_t>(a.outcome_dim) << ": " << a.outcome[i] << " vs "
             << b.outcome[i];
  return ::testing::AssertionSuccess() << a.size << " episodes identical";
}

inline lab::RunSpec mge_efr_spec(sim::Physics physics, uint64_t seed, int episodes,
                                 int bootstrap = 100) {
  lab::RunSpec s;
  s.algorithm = *lab::find_algorithm("MGE-EFR");
  s.physics = physics;
  s.explorer.seed = seed;
  s.explorer.n_bootstrap = bootstrap;
  s.explorer.n_episodes = episodes;
  s.explorer.competence_cap = static_cast<float>(s.algorithm.default_competence_clip);
  return s;
}

// curio-lab's in-process run of `spec` and its archive.
struct InProcess {
  lab::RunResult run;
  ArchiveCopy archive;
};
inline InProcess run_in_process(const lab::RunSpec& spec) {
  InProcess p;
  p.run =
      lab::run_exploration(spec, nullptr, [&](const Explorer& e) { p.archive = copy_archive(e); });
  return p;
}

// Rewrites, drops or adds frames on their way out of the wrapped endpoint (send side), and
// optionally on their way in. Rules run in the thread that sends (or receives).
class FaultyBus final : public hal::CanBus {
 public:
  // Return false to drop `f`; push frames to `extra` to send them after it.
  using Rule = std::function<bool(hal::CanFrame& f, std::vector<hal::CanFrame>& extra)>;

  explicit FaultyBus(hal::CanBus* inner) : inner_(inner) {}
  void set_tx_rule(Rule r) { tx_rule_ = std::move(r); }
  void set_rx_rule(Rule r) { rx_rule_ = std::move(r); }

  hal::CanStatus send_batch(const hal::CanFrame* frames, size_t count, uint64_t deadline_us,
                            size_t* accepted) override {
    if (!tx_rule_) return inner_->send_batch(frames, count, deadline_us, accepted);
    out_.clear();
    for (size_t i = 0; i < count; ++i) {
      hal::CanFrame f = frames[i];
      extra_.clear();
      if (tx_rule_(f, extra_)) out_.push_back(f);
      out_.insert(out_.end(), extra_.begin(), extra_.end());
    }
    if (accepted) *accepted = count;
    if (out_.empty()) return hal::CanStatus::kOk;
    size_t n = 0;
    const hal::CanStatus s = inner_->send_batch(out_.data(), out_.size(), deadline_us, &n);
    if (s != hal::CanStatus::kOk && accepted) *accepted = 0;
    return s;
  }
  hal::CanStatus receive_batch(hal::CanFrame* out, size_t capacity, size_t* received) override {
    return filter_rx(inner_->receive_batch(out, capacity, received), out, received);
  }
  hal::CanStatus wait_readable(uint64_t timeout_us) override {
    return inner_->wait_readable(timeout_us);
  }
  hal::CanStatus receive_wait(hal::CanFrame* out, size_t capacity, size_t* received,
                              uint64_t timeout_us) override {
    return filter_rx(inner_->receive_wait(out, capacity, received, timeout_us), out, received);
  }
  hal::CanStatus set_filters(const hal::CanFilter* filters, size_t count) override {
    return inner_->set_filters(filters, count);
  }
  hal::CanStats stats() const override { return inner_->stats(); }
  hal::BusState state() const override { return inner_->state(); }
  bool carries_fd() const override { return inner_->carries_fd(); }
  uint64_t now_us() const override { return inner_->now_us(); }

 private:
  hal::CanStatus filter_rx(hal::CanStatus s, hal::CanFrame* out, size_t* received) {
    if (s != hal::CanStatus::kOk || !rx_rule_) return s;
    size_t k = 0;
    for (size_t i = 0; i < *received; ++i) {
      hal::CanFrame f = out[i];
      extra_.clear();
      if (rx_rule_(f, extra_)) out[k++] = f;  // extra frames are not supported on receive
    }
    *received = k;
    return k > 0 ? s : hal::CanStatus::kTimeout;
  }

  hal::CanBus* inner_;
  Rule tx_rule_, rx_rule_;
  std::vector<hal::CanFrame> out_, extra_;
};

// The simulated arm (curio-sim serve's node set) polling its bus in a thread. With twin_bus,
// a second arm with the same node ids answers on that bus from the same thread, each arm
// polled in turn: two arms that answer equally fast, so a test of "two arms on one wire" does
// not depend on how the host schedules two arm threads (one can otherwise lag the other by
// a whole bring-up).
class ArmThread {
 public:
  ArmThread(hal::CanBus* bus, const sim::serve::ServeOptions& options,
            hal::CanBus* twin_bus = nullptr) {
    nodes_ = std::make_unique<sim::serve::ArmNodes>(bus, options);
    if (twin_bus == nullptr) {
      thread_ = std::thread([this] { nodes_->run(stop_); });
      return;
    }
    twin_ = std::make_unique<sim::serve::ArmNodes>(twin_bus, options);
    thread_ = std::thread([this] {
      while (!stop_.load(std::memory_order_relaxed)) {
        nodes_->poll(500);
        twin_->poll(500);
      }
    });
  }
  ~ArmThread() { stop(); }
  void stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  // Only after stop().
  const sim::serve::ArmNodes& nodes() const { return *nodes_; }

 private:
  std::atomic<bool> stop_{false};
  std::unique_ptr<sim::serve::ArmNodes> nodes_, twin_;
  std::thread thread_;
};

inline sim::serve::ServeOptions serve_options(const lab::RunSpec& spec) {
  sim::serve::ServeOptions o;
  o.physics = spec.physics;
  o.world = spec.world;
  o.seed = spec.explorer.seed;
  return o;
}

// Timeouts short enough that fault tests finish quickly, long enough that a loaded machine
// does not add faults of its own (no assertion is about time).
inline ControllerConfig fast_fault_config() {
  ControllerConfig c;
  c.heartbeat_producer_ms = 50;
  c.heartbeat_timeout_us = 400'000;
  c.sdo_timeout_us = 200'000;
  c.feedback_timeout_us = 200'000;
  c.capture_timeout_us = 500'000;
  c.recovery_timeout_us = 5'000'000;
  c.max_attempts = 4;
  return c;
}

// The controller tests' ports start above the bus tests' (tests/hal), so that the two running
// in parallel rarely probe the same ports.
inline uint16_t free_udp_base(unsigned count) {
  return hal::test::free_udp_base(count, 42000, 1200);
}

// The same run over a bus pair: `arm_bus` for the simulated arm (maybe a FaultyBus in front
// of an endpoint), `controller_bus` for the controller.
inline host::BusRunResult run_with_arm(hal::CanBus* arm_bus, hal::CanBus* controller_bus,
                                       const lab::RunSpec& spec, const ControllerConfig& config,
                                       ArchiveCopy* archive,
                                       sim::serve::ServeCounters* arm_counters = nullptr,
                                       hal::CanBus* twin_arm_bus = nullptr) {
  ArmThread arm(arm_bus, serve_options(spec), twin_arm_bus);
  host::BusRunOptions o;
  o.spec = spec;
  o.controller = config;
  host::BusRunResult r =
      host::run_over_bus(controller_bus, o, [&](const Explorer& e) { *archive = copy_archive(e); });
  arm.stop();
  if (arm_counters) *arm_counters = arm.nodes().counters();
  return r;
}

}  // namespace curio::app::test
