// The explorer's outcome of an episode's final state (encoder μ or engineered features).
#include "firmware/app/episode_outcome.hpp"

#include "firmware/explore/module_layouts.hpp"
#include "firmware/nn/encoder.hpp"

namespace curio::app {

static_assert(kLatentDim == nn::kLatents, "the encoder's μ is the learned outcome");

bool episode_outcome(const FinalPositions& p, nn::Encoder* encoder, const uint8_t* camera_frame,
                     float* outcome) {
  if (encoder != nullptr) return encoder->encode(camera_frame, outcome) == nn::Status::kOk;
  outcome[kEfrDistractorX] = static_cast<float>(p.distractor_x);
  outcome[kEfrDistractorY] = static_cast<float>(p.distractor_y);
  outcome[kEfrBallX] = static_cast<float>(p.ball_x);
  outcome[kEfrBallY] = static_cast<float>(p.ball_y);
  return true;
}

}  // namespace curio::app
