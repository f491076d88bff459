// Parity over a kernel CAN interface: the controller and the simulated arm (curio-sim serve's
// node set) over a real kernel CAN FD interface (SocketCAN vcan0), ≥ 200 episodes, and the
// archive equals curio-lab's in-process archive bit for bit. Needs AF_CAN: runs inside
// User-mode Linux (ctest label "vcan", tests/uml/run-in-uml.sh, started by uml_vcan_suite);
// elsewhere it skips with the reason (CURIO_REQUIRE_VCAN makes that a failure).
#include <gtest/gtest.h>

#include <cstdlib>

#include "tests/app/app_test_util.hpp"
#include "hal/linux/open_bus.hpp"

namespace curio::app::test {
namespace {

std::string vcan_url() {
  const char* env = std::getenv("CURIO_VCAN");
  return std::string("socketcan:") + (env ? env : "vcan0");
}

class VcanParity : public ::testing::TestWithParam<sim::Physics> {};

TEST_P(VcanParity, ControllerAndArmOverVcanMatchInProcess) {
  std::string why;
  auto arm_end = hal::open_bus(vcan_url(), &why);
  auto controller_end = arm_end ? hal::open_bus(vcan_url(), &why) : nullptr;
  if (!controller_end && std::getenv("CURIO_REQUIRE_VCAN"))
    FAIL() << "SocketCAN unavailable: " << why;
  if (!controller_end)
    GTEST_SKIP() << "SocketCAN unavailable (" << why << "): run inside User-mode Linux";
  // 100 bootstrap + 100 exploration = 200 episodes of MGE-EFR.
  const lab::RunSpec spec = mge_efr_spec(GetParam(), 5, 100, 100);
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
      "vcan %s: %.0f episodes in %.2f s = %.1f episodes/s, %.0f frames/episode at the controller\n",
      sim::physics_name(GetParam()), n, r.seconds, n / r.seconds,
      static_cast<double>(r.frames_sent + r.frames_received) / n);
}

INSTANTIATE_TEST_SUITE_P(Physics, VcanParity,
                         ::testing::Values(sim::Physics::kKinematic, sim::Physics::kOde),
                         [](const auto& info) {
                           return std::string(sim::physics_name(info.param));
                         });

}  // namespace
}  // namespace curio::app::test
