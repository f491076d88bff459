// Parity: for the same seed, the run over the bus archives exactly what curio-lab's
// in-process run archives (θ and outcomes, bit for bit), and records the same curves.
#include <gtest/gtest.h>

#include "tests/app/app_test_util.hpp"
#include "hal/linux/udp_bus.hpp"
#include "hal/linux/open_bus.hpp"

namespace curio::app::test {
namespace {

// 100 bootstrap + 150 exploration episodes of MGE-EFR: 250 ≥ 200.
constexpr int kEpisodes = 150;

// Default protocol, with timeouts long enough that a loaded 2-core machine descheduling a
// thread for a while is not a fault (faults are fault_test.cpp's subject).
ControllerConfig patient() {
  ControllerConfig c;
  c.heartbeat_timeout_us = 3'000'000;
  c.feedback_timeout_us = 1'000'000;
  c.sdo_timeout_us = 1'000'000;
  return c;
}

void expect_same_results(const lab::RunResult& bus, const lab::RunResult& local) {
  ASSERT_TRUE(bus.error.empty()) << bus.error;
  EXPECT_EQ(bus.checkpoints, local.checkpoints);
  EXPECT_EQ(bus.ratio, local.ratio);
  EXPECT_EQ(bus.grasps, local.grasps);
  EXPECT_EQ(bus.final_ball, local.final_ball);
  EXPECT_EQ(bus.interest_episodes, local.interest_episodes);
  EXPECT_EQ(bus.interest, local.interest);
  EXPECT_EQ(bus.module_choices, local.module_choices);
  ASSERT_EQ(bus.exploits.size(), local.exploits.size());
  for (size_t i = 0; i < bus.exploits.size(); ++i) {
    EXPECT_EQ(bus.exploits[i].episode, local.exploits[i].episode);
    EXPECT_EQ(bus.exploits[i].module, local.exploits[i].module);
    EXPECT_TRUE(same_bits(bus.exploits[i].progress, local.exploits[i].progress)) << "exploit " << i;
  }
}

class Parity : public ::testing::TestWithParam<sim::Physics> {};

// Runs `spec` over the bus pair with patient timeouts and expects, without a fault, the
// archive and the curves of the in-process run `local`.
void expect_bus_run_as_in_process(hal::CanBus* arm_end, hal::CanBus* controller_end,
                                  const lab::RunSpec& spec, const InProcess& local,
                                  host::BusRunResult* r) {
  ArchiveCopy archive;
  *r = run_with_arm(arm_end, controller_end, spec, patient(), &archive);
  ASSERT_TRUE(r->run.error.empty()) << r->run.error;
  EXPECT_EQ(archive.size, spec.explorer.n_bootstrap + spec.explorer.n_episodes);
  EXPECT_TRUE(archives_identical(archive, local.archive));
  expect_same_results(r->run, local.run);
  EXPECT_EQ(r->counters.fault_total, 0u) << host::fault_summary(r->counters);
}

TEST_P(Parity, LoopbackBusArchiveIsIdenticalToInProcess) {
  const lab::RunSpec spec = mge_efr_spec(GetParam(), 11, kEpisodes);
  const InProcess local = run_in_process(spec);
  auto wire = hal::LoopbackBus::create();
  auto arm_end = wire->open();
  auto controller_end = wire->open();
  host::BusRunResult r;
  ASSERT_NO_FATAL_FAILURE(
      expect_bus_run_as_in_process(arm_end.get(), controller_end.get(), spec, local, &r));
  EXPECT_GT(r.run.grasps.back(), 0) << "the run should grasp the ball at least once";
  std::printf("%s loopback: %zu episodes, %llu frames sent, %llu received\n",
              sim::physics_name(GetParam()), r.run.final_ball.size(),
              static_cast<unsigned long long>(r.frames_sent),
              static_cast<unsigned long long>(r.frames_received));
}

TEST_P(Parity, UdpBusArchiveIsIdenticalToInProcess) {
  const lab::RunSpec spec = mge_efr_spec(GetParam(), 12, kEpisodes);
  const InProcess local = run_in_process(spec);
  const uint16_t base = free_udp_base(4);
  ASSERT_NE(base, 0) << "no free UDP port range on 127.0.0.1";
  std::string error;
  auto arm_end = hal::UdpBus::open(base, 4, &error);
  ASSERT_TRUE(arm_end) << error;
  auto controller_end = hal::UdpBus::open(base, 4, &error);
  ASSERT_TRUE(controller_end) << error;
  host::BusRunResult r;
  expect_bus_run_as_in_process(arm_end.get(), controller_end.get(), spec, local, &r);
}

// The classic profile (classic-only endpoints: the ground truth in five 8-byte frames): the
// same archive as in-process, over loopback and over UDP.
TEST_P(Parity, ClassicProfileArchiveIsIdenticalToInProcess) {
  const lab::RunSpec spec = mge_efr_spec(GetParam(), 14, kEpisodes);
  const InProcess local = run_in_process(spec);
  {
    auto wire = hal::LoopbackBus::create();
    auto arm_end = wire->open(false);
    auto controller_end = wire->open(false);
    host::BusRunResult r;
    ASSERT_NO_FATAL_FAILURE(
        expect_bus_run_as_in_process(arm_end.get(), controller_end.get(), spec, local, &r));
  }
  const uint16_t base = free_udp_base(4);
  ASSERT_NE(base, 0) << "no free UDP port range on 127.0.0.1";
  std::string error;
  auto arm_end = hal::open_bus("udp:127.0.0.1:" + std::to_string(base) + "?ports=4&classic=1",
                               &error);
  ASSERT_TRUE(arm_end) << error;
  auto controller_end =
      hal::open_bus("udp:127.0.0.1:" + std::to_string(base) + "?ports=4&classic=1", &error);
  ASSERT_TRUE(controller_end) << error;
  ASSERT_FALSE(controller_end->carries_fd());
  host::BusRunResult r;
  expect_bus_run_as_in_process(arm_end.get(), controller_end.get(), spec, local, &r);
  EXPECT_EQ(controller_end->stats().errors, 0u) << "no FD frame reached a classic endpoint";
}

// The camera frame travels too (ISO-TP: 196 FD frames or 1,757 classic ones per episode);
// outcomes still come from the ground truth for engineered features, so the archive is
// unchanged.
class ParityWithImages : public ::testing::TestWithParam<protocol::CanProfile> {};

TEST_P(ParityWithImages, CameraFramesOverIsoTp) {
  const lab::RunSpec spec = mge_efr_spec(sim::Physics::kKinematic, 13, 50, 50);
  const InProcess local = run_in_process(spec);
  auto wire = hal::LoopbackBus::create();
  const bool fd = GetParam() == protocol::CanProfile::kFd;
  auto arm_end = wire->open(fd);
  auto controller_end = wire->open(fd);
  ControllerConfig config = patient();
  config.want_image = true;
  ArchiveCopy archive;
  sim::serve::ServeCounters arm;
  const host::BusRunResult r =
      run_with_arm(arm_end.get(), controller_end.get(), spec, config, &archive, &arm);
  ASSERT_TRUE(r.run.error.empty()) << r.run.error;
  EXPECT_TRUE(archives_identical(archive, local.archive));
  EXPECT_EQ(r.image.completed, 100u);
  EXPECT_EQ(arm.images_sent, 100u);
  EXPECT_EQ(arm.image_errors, 0u);
}

INSTANTIATE_TEST_SUITE_P(Profiles, ParityWithImages,
                         ::testing::Values(protocol::CanProfile::kFd,
                                           protocol::CanProfile::kClassic),
                         [](const auto& info) { return std::string(to_string(info.param)); });

INSTANTIATE_TEST_SUITE_P(Physics, Parity,
                         ::testing::Values(sim::Physics::kKinematic, sim::Physics::kOde),
                         [](const auto& info) {
                           return std::string(sim::physics_name(info.param));
                         });

}  // namespace
}  // namespace curio::app::test
