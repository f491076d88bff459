// app::episode_outcome, the one final state → outcome step of the controller and curio-lab:
// engineered features in the kEfr* layout, the encoder's μ of the frame, and a refusal.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>

#include "firmware/app/episode_outcome.hpp"
#include "firmware/explore/module_layouts.hpp"
#include "firmware/nn/encoder.hpp"
#include "sim/camera.hpp"
#include "sim/render.hpp"
#include "tests/nn/synthetic_firmware_model.hpp"

namespace curio::app::test {
namespace {

TEST(EpisodeOutcome, EngineeredFeaturesAreTheFloatOfThePositionsInEfrLayout) {
  const FinalPositions p{.ball_x = 0.1234567890123,
                         .ball_y = -0.75,
                         .distractor_x = 1.0 / 3.0,
                         .distractor_y = -2.5e-9};
  float outcome[kMaxOutcomeDim];
  for (float& o : outcome) o = 99.0f;
  ASSERT_TRUE(episode_outcome(p, nullptr, nullptr, outcome));
  EXPECT_EQ(outcome[kEfrDistractorX], static_cast<float>(p.distractor_x));
  EXPECT_EQ(outcome[kEfrDistractorY], static_cast<float>(p.distractor_y));
  EXPECT_EQ(outcome[kEfrBallX], static_cast<float>(p.ball_x));
  EXPECT_EQ(outcome[kEfrBallY], static_cast<float>(p.ball_y));
  EXPECT_EQ(outcome[0], static_cast<float>(1.0 / 3.0)) << "[distractor x, y, ball x, y]";
  EXPECT_EQ(outcome[3], -0.75f);
  for (int i = kEfrOutcomeDim; i < kMaxOutcomeDim; ++i) EXPECT_EQ(outcome[i], 99.0f) << i;
}

TEST(EpisodeOutcome, WithAnEncoderItIsTheEncodersMuOfTheFrame) {
  auto image = std::make_unique<sim::Image>();
  auto frame = std::make_unique<sim::CameraFrame>();
  sim::render_scene({0.3, -0.2}, {-0.5, 0.4}, image.get());
  sim::to_camera_frame(*image, frame.get());
  nn::Encoder direct(nn::testing::synthetic_firmware_model());
  float expected[kLatentDim];
  ASSERT_EQ(direct.encode(frame->data(), expected), nn::Status::kOk);

  nn::Encoder encoder(nn::testing::synthetic_firmware_model());
  // The positions are not used: learned goal spaces see only the frame.
  const FinalPositions p{.ball_x = 7, .ball_y = 7, .distractor_x = 7, .distractor_y = 7};
  float outcome[kMaxOutcomeDim] = {};
  ASSERT_TRUE(episode_outcome(p, &encoder, frame->data(), outcome));
  EXPECT_EQ(std::memcmp(outcome, expected, sizeof expected), 0);
  EXPECT_EQ(encoder.encodes(), 1u);
}

TEST(EpisodeOutcome, AnEncoderRefusalIsFalseAndLeavesTheOutcome) {
  nn::Encoder encoder(nn::testing::synthetic_firmware_model());
  float outcome[kMaxOutcomeDim];
  for (float& o : outcome) o = 5.0f;
  EXPECT_FALSE(episode_outcome(FinalPositions{}, &encoder, nullptr, outcome));
  for (float o : outcome) EXPECT_EQ(o, 5.0f);
}

}  // namespace
}  // namespace curio::app::test
