// Learned goal spaces over the bus: the camera frame travels by ISO-TP into the controller's
// static buffer and the int8 encoder's μ is the outcome. With the synthetic int8 model of the
// nn tests (no trained weights are needed), the bus run archives exactly what the in-process
// path (render → to_camera_frame → encoder, as curio-lab's learned runs do) archives.
#include <gtest/gtest.h>

#include <memory>

#include "tests/app/app_test_util.hpp"
#include "firmware/explore/module_layouts.hpp"
#include "firmware/nn/encoder.hpp"
#include "sim/camera.hpp"
#include "tests/nn/synthetic_firmware_model.hpp"

namespace curio::app::test {
namespace {

ExplorerConfig mge_latent_config(uint64_t seed) {
  ExplorerConfig c;
  uint8_t order[kLatentDim];
  for (int i = 0; i < kLatentDim; ++i)
    order[i] = static_cast<uint8_t>(nn::testing::synthetic_kl_order()[i]);
  EXPECT_EQ(set_latent_modules(c, order, 2), Status::kOk);
  c.n_bootstrap = 40;
  c.n_episodes = 40;
  c.seed = seed;
  return c;
}

// Both profiles: the frame in 64-byte FD or 8-byte classic ISO-TP frames, the same outcomes.
class LearnedParity : public ::testing::TestWithParam<protocol::CanProfile> {};

TEST_P(LearnedParity, EncoderOutcomesOverTheBusEqualInProcess) {
  constexpr uint64_t kSeed = 8;
  const ExplorerConfig config = mge_latent_config(kSeed);
  // In-process: the quantized rollout, the camera frame, the encoder.
  auto local = std::make_unique<Explorer>();
  ASSERT_EQ(local->init(config), Status::kOk);
  {
    auto world = sim::make_world(sim::Physics::kOde, {}, sim::world_seed_for_run(kSeed));
    nn::Encoder encoder(nn::testing::synthetic_firmware_model());
    auto image = std::make_unique<sim::Image>();
    auto frame = std::make_unique<sim::CameraFrame>();
    float theta[kThetaDim], mu[kLatentDim];
    while (!local->done()) {
      ASSERT_EQ(local->propose(theta), Status::kOk);
      const sim::SceneState s = world->rollout_joint_targets(theta);
      sim::render_scene(s.ball, s.distractor, image.get());
      sim::to_camera_frame(*image, frame.get());
      ASSERT_EQ(encoder.encode(frame->data(), mu), nn::Status::kOk);
      ASSERT_EQ(local->observe(mu), Status::kOk);
    }
  }
  // Over the loopback bus.
  auto bus_explorer = std::make_unique<Explorer>();
  ASSERT_EQ(bus_explorer->init(config), Status::kOk);
  auto wire = hal::LoopbackBus::create();
  const bool fd = GetParam() == protocol::CanProfile::kFd;
  auto arm_end = wire->open(fd);
  auto controller_end = wire->open(fd);
  sim::serve::ServeOptions so;
  so.physics = sim::Physics::kOde;
  so.seed = kSeed;
  ArmThread arm(arm_end.get(), so);
  nn::Encoder encoder(nn::testing::synthetic_firmware_model());
  auto controller = std::make_unique<Controller>();
  ASSERT_EQ(
      controller->init(controller_end.get(), bus_explorer.get(), ControllerConfig{}, &encoder),
      AppStatus::kOk);
  ASSERT_TRUE(controller->config().want_image) << "learned goal spaces need the frame";
  ASSERT_EQ(controller->start_arm(), AppStatus::kOk);
  while (!bus_explorer->done()) ASSERT_EQ(controller->run_episode(), AppStatus::kOk);
  arm.stop();
  EXPECT_EQ(controller->image_counters().completed, 80u);
  EXPECT_EQ(encoder.encodes(), 80u);
  EXPECT_TRUE(archives_identical(copy_archive(*bus_explorer), copy_archive(*local)));
}

INSTANTIATE_TEST_SUITE_P(Profiles, LearnedParity,
                         ::testing::Values(protocol::CanProfile::kFd,
                                           protocol::CanProfile::kClassic),
                         [](const auto& info) { return std::string(to_string(info.param)); });

}  // namespace
}  // namespace curio::app::test
