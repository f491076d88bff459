// The episode's capture: request → ground truth (+ the camera frame over ISO-TP into a static
// buffer) → checked → the explorer's outcome and the record's final positions.
#pragma once
#include <cstdint>

#include "firmware/app/canopen_master.hpp"
#include "firmware/app/frame_source.hpp"
#include "firmware/protocol/arm_messages.hpp"
#include "firmware/protocol/isotp.hpp"

namespace curio::nn {
class Encoder;
}

namespace curio::app {

class EpisodeCapture final : public Wait {
 public:
  explicit EpisodeCapture(CanOpenMaster* master);

  // Captures the end of `episode` (the frame too when config().want_image); on success the
  // outcome (the encoder's μ of the frame, or the engineered features of the ground truth)
  // and record's ball, distractor and grasped. false on a fault (raised).
  bool capture(uint32_t episode, nn::Encoder* encoder, float* outcome, EpisodeRecord* record);

  const protocol::IsoTpCounters& image_counters() const { return image_rx_.counters(); }

  // The camera on the controller's computer (config().camera_on_bus false): the frame comes
  // from it, the first that arrived after the settle time; there is no ground truth (the
  // record's ball and distractor are NaN, grasped false).
  void set_frame_source(FrameSource* source) { source_ = source; }

  // The master's wait: the ground truth of this episode and (if wanted) one whole frame. The
  // master also hands it what other waits did not take: a second ground truth for the last
  // captured episode, or a second camera's transfer after its frame was whole, raises
  // kDuplicateCapture (fatal) unless an earlier request for the episode went unanswered.
  bool done() const override { return ground_truth_ok_ && image_ok_; }
  void poll(uint64_t now) override;
  bool on_ground_truth(const protocol::GroundTruth& g) override;
  bool on_camera_frame(const hal::CanFrame& f, uint64_t now) override;

 private:
  CanOpenMaster* master_;
  void second_answer();

  uint32_t episode_ = 0;
  bool waiting_ = false;                // inside capture()'s wait
  bool answered_ = true;                // the last capture ended with all it waited for
  bool late_answers_possible_ = false;  // an earlier request for this episode went unanswered
  bool image_received_ = false;         // this capture's frame arrived whole
  bool ground_truth_ok_ = false;
  protocol::GroundTruth ground_truth_;
  bool image_ok_ = false;
  uint8_t image_[protocol::kCameraImageBytes] = {};
  protocol::IsoTpReceiver image_rx_;
  FrameSource* source_ = nullptr;
  bool local_ = false;  // this capture waits for the FrameSource

  bool capture_local(nn::Encoder* encoder, float* outcome, EpisodeRecord* record);
};

}  // namespace curio::app
