// The explorer's outcome of an episode's final state: the one step from final state to outcome,
// shared by the controller (ground truth and camera frame over the bus) and curio-lab's
// in-process rollout (sim::SceneState and the rendered frame), so both archive the same.
#pragma once
#include <cstdint>

namespace curio::nn {
class Encoder;
}

namespace curio::app {

// Where the ball and the distractor ended (the scene's ground truth).
struct FinalPositions {
  double ball_x = 0, ball_y = 0;
  double distractor_x = 0, distractor_y = 0;
};

// With an encoder (learned goal spaces): its μ of `camera_frame` (64×64×3 bytes; the
// positions are not used). Without (engineered features): the float of the positions in the
// kEfr* layout [distractor x, distractor y, ball x, ball y]; camera_frame is not used.
// false only when the encoder refuses the frame (outcome then untouched).
bool episode_outcome(const FinalPositions& p, nn::Encoder* encoder, const uint8_t* camera_frame,
                     float* outcome);

}  // namespace curio::app
