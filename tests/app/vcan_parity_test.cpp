// Parity over a kernel CAN interface: the controller and the simulated arm (curio-sim serve's
// node set) over a real kernel CAN FD interface (SocketCAN vcan0), ≥ 200 episodes, and the
// archive equals curio-lab's in-process archive bit for bit; and the same over a classic
// interface (vcan_classic, MTU 16: the classic profile), which so equals the FD run too. Needs AF_CAN: runs inside
// User-mode Linux (ctest label "vcan", tests/uml/run-in-uml.sh, started by uml_vcan_suite);
// elsewhere it skips with the reason (CURIO_REQUIRE_VCAN makes that a failure).
#include <gtest/gtest.h>

#include <cstdlib>
#include <tuple>

#include "tests/app/app_test_util.hpp"
#include "hal/linux/open_bus.hpp"

namespace curio::app::test {
namespace {

std::string vcan_url(bool classic) {
  const char* env = std::getenv(classic ? "CURIO_VCAN_CLASSIC" : "CURIO_VCAN");
  return std::string("socketcan:") + (env ? env : classic ? "vcan_classic" : "vcan0");
}

// (physics, classic interface)
class VcanParity : public ::testing::TestWithParam<std::tuple<sim::Physics, bool>> {};

TEST_P(VcanParity, ControllerAndArmOverVcanMatchInProcess) {
  const auto [physics, classic] = GetParam();
  std::string why;
  auto arm_end = hal::open_bus(vcan_url(classic), &why);
  auto controller_end = arm_end ? hal::open_bus(vcan_url(classic), &why) : nullptr;
  if (!controller_end && std::getenv("CURIO_REQUIRE_VCAN"))
    FAIL() << "SocketCAN unavailable: " << why;
  if (!controller_end)
    GTEST_SKIP() << "SocketCAN unavailable (" << why << "): run inside User-mode Linux";
  ASSERT_EQ(controller_end->carries_fd(), !classic) << "the interface's MTU decides the profile";
  // 100 bootstrap + 100 exploration = 200 episodes of MGE-EFR.
  const lab::RunSpec spec = mge_efr_spec(physics, 5, 100, 100);
  const InProcess local = run_in_process(spec);
  ControllerConfig config;  // the defaults; generous enough for UML's slow syscalls
  config.feedback_timeout_us = 1'000'000;
  config.heartbeat_timeout_us = 3'000'000;
  config.sdo_timeout_us = 1'000'000;
  ArchiveCopy archive;
  const host::BusRunResult r =
      run_with_arm(arm_end.get(), controller_end.get(), spec, config, &archive);
  ASSERT_TRUE(r.run.error.empty()) << r.run.error;
  EXPECT_EQ(archive.size, 200);
  EXPECT_TRUE(archives_identical(archive, local.archive));
  EXPECT_EQ(r.run.ratio, local.run.ratio);
  EXPECT_EQ(r.counters.fault_total, 0u) << host::fault_summary(r.counters);
  const double n = static_cast<double>(r.run.final_ball.size());
  std::printf(
      "vcan %s %s: %.0f episodes in %.2f s = %.1f episodes/s, %.0f frames/episode at the "
      "controller\n",
      sim::physics_name(physics), classic ? "classic" : "fd", n, r.seconds, n / r.seconds,
      static_cast<double>(r.frames_sent + r.frames_received) / n);
}

INSTANTIATE_TEST_SUITE_P(Physics, VcanParity,
                         ::testing::Combine(::testing::Values(sim::Physics::kKinematic,
                                                              sim::Physics::kOde),
                                            ::testing::Bool()),
                         [](const auto& info) {
                           return std::string(sim::physics_name(std::get<0>(info.param))) +
                                  (std::get<1>(info.param) ? "_classic" : "_fd");
                         });

}  // namespace
}  // namespace curio::app::test
