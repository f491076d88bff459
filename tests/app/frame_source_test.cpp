// A camera on the controller's computer (ControllerConfig::camera_on_bus false, a FrameSource):
// the arm comes up with its seven joints only (the serve runs no camera node), no frame goes
// to node 32, and the archive is the in-process run's when the source gives the final scenes'
// frames; a source that fails, or gives no fresh frame in time, stops the run without a replay
// (fault camera_failed); engineered features, which need the ground truth, are refused.
#include <string>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "firmware/app/frame_source.hpp"
#include "firmware/explore/module_layouts.hpp"
#include "firmware/nn/encoder.hpp"
#include "sim/camera.hpp"
#include "tests/app/app_test_util.hpp"
#include "tests/nn/synthetic_firmware_model.hpp"

namespace curio::app::test {
namespace {

constexpr uint64_t kSeed = 11;

ExplorerConfig latent_config() {
  ExplorerConfig c;
  uint8_t order[kLatentDim];
  for (int i = 0; i < kLatentDim; ++i)
    order[i] = static_cast<uint8_t>(nn::testing::synthetic_kl_order()[i]);
  EXPECT_EQ(set_latent_modules(c, order, 2), Status::kOk);
  c.n_bootstrap = 20;
  c.n_episodes = 20;
  c.seed = kSeed;
  return c;
}

// Hands out prepared frames, one per request: fresh after `pending_polls` polls; kFailed from
// request number `fail_at` on (-1: never).
class ScriptedCamera final : public FrameSource {
 public:
  std::vector<sim::CameraFrame> frames;
  int fail_at = -1;
  int pending_polls = 3;
  int requests = 0;
  uint32_t last_settle_us = 0;

  void request_frame(uint32_t settle_us) override {
    ++requests;
    polls_ = 0;
    last_settle_us = settle_us;
  }
  FrameStatus poll_frame(uint8_t* frame) override {
    if (fail_at >= 0 && requests > fail_at) return FrameStatus::kFailed;
    if (pending_polls < 0 || ++polls_ <= pending_polls) return FrameStatus::kPending;
    const sim::CameraFrame& f = frames.at(static_cast<size_t>(requests - 1));
    std::copy(f.begin(), f.end(), frame);
    return FrameStatus::kFresh;
  }

 private:
  int polls_ = 0;
};

// The in-process run (rollout, render, camera bytes, encoder): its archive and every episode's
// final frame.
std::unique_ptr<Explorer> in_process(const ExplorerConfig& config, std::vector<sim::CameraFrame>* frames) {
  auto e = std::make_unique<Explorer>();
  EXPECT_EQ(e->init(config), Status::kOk);
  auto world = sim::make_world(sim::Physics::kOde, {}, sim::world_seed_for_run(kSeed));
  nn::Encoder encoder(nn::testing::synthetic_firmware_model());
  auto image = std::make_unique<sim::Image>();
  float theta[kThetaDim], mu[kLatentDim];
  while (!e->done()) {
    EXPECT_EQ(e->propose(theta), Status::kOk);
    const sim::SceneState s = world->rollout_joint_targets(theta);
    sim::render_scene(s.ball, s.distractor, image.get());
    frames->emplace_back();
    sim::to_camera_frame(*image, &frames->back());
    EXPECT_EQ(encoder.encode(frames->back().data(), mu), nn::Status::kOk);
    EXPECT_EQ(e->observe(mu), Status::kOk);
  }
  return e;
}

struct BusSide {
  std::shared_ptr<hal::LoopbackBus> wire = hal::LoopbackBus::create();
  std::unique_ptr<hal::CanBus> arm_end = wire->open(true);
  std::unique_ptr<hal::CanBus> controller_end = wire->open(true);
};

sim::serve::ServeOptions no_camera_node() {
  sim::serve::ServeOptions so;
  so.physics = sim::Physics::kOde;
  so.seed = kSeed;
  so.camera_node = false;
  return so;
}

// "feedback_timeout 2 (last node 3)": the faults by name, for a failure's message.
std::string faults_text(const ControllerCounters& c) {
  std::string s;
  for (size_t i = 1; i < kFaultKinds; ++i)
    if (c.faults[i] > 0)
      s += std::string(to_string(static_cast<Fault>(i))) + " " + std::to_string(c.faults[i]) + "; ";
  return s + "last node " + std::to_string(c.last_fault_node) + ", last EMCY " +
         std::to_string(c.last_emcy_code) + " from node " + std::to_string(c.last_emcy_node);
}

ControllerConfig local_camera_config() {
  ControllerConfig c;
  c.camera_on_bus = false;
  c.frame_settle_us = 1'000;
  c.frame_timeout_us = 200'000;
  return c;
}

TEST(LocalCamera, TheArmComesUpWithoutNode32AndArchivesTheInProcessRun) {
  const ExplorerConfig config = latent_config();
  ScriptedCamera camera;
  const auto local = in_process(config, &camera.frames);
  auto explorer = std::make_unique<Explorer>();
  ASSERT_EQ(explorer->init(config), Status::kOk);
  BusSide bus;
  ArmThread arm(bus.arm_end.get(), no_camera_node());
  nn::Encoder encoder(nn::testing::synthetic_firmware_model());
  auto controller = std::make_unique<Controller>();
  ASSERT_EQ(controller->init(bus.controller_end.get(), explorer.get(), local_camera_config(), &encoder),
            AppStatus::kOk);
  controller->set_frame_source(&camera);
  ASSERT_EQ(controller->start_arm(), AppStatus::kOk) << "no wait for node 32";
  EXPECT_EQ(controller->query_physics(), 0xFF) << "no camera node to ask";
  while (!explorer->done()) ASSERT_EQ(controller->run_episode(), AppStatus::kOk);
  controller->stop_arm();
  arm.stop();
  EXPECT_EQ(camera.requests, 40);
  EXPECT_EQ(camera.last_settle_us, 1'000u);
  EXPECT_EQ(controller->counters().fault_total, 0u) << faults_text(controller->counters());
  EXPECT_TRUE(std::isnan(controller->last_episode().ball[0])) << "no ground truth";
  const sim::serve::ServeCounters& served = arm.nodes().counters();
  EXPECT_EQ(served.captures, 0u);
  // The serve's only foreign frames are the controller's heartbeats (0x77F, which the joints
  // consume): nothing was sent to node 32.
  EXPECT_EQ(served.foreign, controller->counters().heartbeats_sent) << "nothing sent to node 32";
  EXPECT_EQ(served.episodes, 40u) << "the episodes started themselves";
  EXPECT_TRUE(archives_identical(copy_archive(*explorer), copy_archive(*local)));
}

TEST(LocalCamera, AFailedCameraStopsTheRunWithoutAReplay) {
  for (const bool never_fresh : {false, true}) {
    const ExplorerConfig config = latent_config();
    ScriptedCamera camera;
    in_process(config, &camera.frames);
    if (never_fresh) camera.pending_polls = -1; else camera.fail_at = 5;
    auto explorer = std::make_unique<Explorer>();
    ASSERT_EQ(explorer->init(config), Status::kOk);
    BusSide bus;
    ArmThread arm(bus.arm_end.get(), no_camera_node());
    nn::Encoder encoder(nn::testing::synthetic_firmware_model());
    auto controller = std::make_unique<Controller>();
    ASSERT_EQ(controller->init(bus.controller_end.get(), explorer.get(), local_camera_config(), &encoder),
              AppStatus::kOk);
    controller->set_frame_source(&camera);
    ASSERT_EQ(controller->start_arm(), AppStatus::kOk);
    AppStatus s = AppStatus::kOk;
    while (s == AppStatus::kOk && !explorer->done()) s = controller->run_episode();
    controller->stop_arm();
    arm.stop();
    EXPECT_EQ(s, AppStatus::kEpisodeFailed) << "never fresh: " << never_fresh;
    EXPECT_EQ(explorer->episode(), never_fresh ? 0 : 5) << "nothing archived from the failed capture";
    const ControllerCounters& c = controller->counters();
    EXPECT_EQ(c.faults[static_cast<size_t>(Fault::kCameraFailed)], 1u);
    EXPECT_EQ(c.fault_total, 1u);
    EXPECT_EQ(c.replays, 0u) << "a camera that failed gives no more frames: no replay";
  }
}

TEST(LocalCamera, EngineeredFeaturesNeedTheCameraNode) {
  ExplorerConfig config;
  ASSERT_EQ(set_efr_modules(config, Algorithm::kMge), Status::kOk);
  config.n_bootstrap = 5;
  config.n_episodes = 5;
  Explorer explorer;
  ASSERT_EQ(explorer.init(config), Status::kOk);
  BusSide bus;
  Controller controller;
  EXPECT_EQ(controller.init(bus.controller_end.get(), &explorer, local_camera_config(), nullptr),
            AppStatus::kInvalidArgument);
  EXPECT_EQ(controller.init(bus.controller_end.get(), &explorer, ControllerConfig{}, nullptr), AppStatus::kOk);
}

}  // namespace
}  // namespace curio::app::test
