// The episode's capture: ground truth and camera frame in, outcome out.
#include "firmware/app/episode_capture.hpp"

#include <cmath>
#include <limits>

#include "firmware/app/episode_outcome.hpp"

namespace curio::app {

using hal::CanFrame;
using namespace protocol;

static_assert(kCameraImageBytes == sizeof(uint8_t) * 64 * 64 * 3, "one camera frame");

EpisodeCapture::EpisodeCapture(CanOpenMaster* master)
    : master_(master),
      image_rx_(camera_link_for_controller(CanProfile::kFd), image_, sizeof image_) {
  master_->set_capture(this);
}

// A camera answers each capture request once, with one ground truth and one frame: a second
// answer is a second camera, or a third process forging the scene. Unless an earlier request
// for this episode ended unanswered (its late answer may come now), that is a fatal fault,
// whether it comes while this capture waits or after the controller moved on.
void EpisodeCapture::second_answer() {
  if (!late_answers_possible_) master_->raise(Fault::kDuplicateCapture, kCameraNode);
}

void EpisodeCapture::poll(uint64_t now) {
  if (local_ && !image_ok_) {
    const FrameStatus s = source_->poll_frame(image_);
    if (s == FrameStatus::kFresh) image_ok_ = true;
    if (s == FrameStatus::kFailed) master_->raise(Fault::kCameraFailed, 0);
    return;
  }
  if (!image_rx_.busy()) return;
  IsoTpReply reply;
  if (image_rx_.poll(now, &reply) == IsoTpStatus::kTimeout)
    master_->raise(Fault::kCaptureTimeout, kCameraNode);
  if (reply.valid) master_->send(&reply.frame, 1);
}

bool EpisodeCapture::on_ground_truth(const GroundTruth& g) {
  if (g.episode != episode_) return false;  // another episode's (stale)
  if (ground_truth_ok_) {
    second_answer();
    return false;
  }
  if (!waiting_) return false;  // the late answer of a capture that ended without it
  ground_truth_ = g;
  ground_truth_ok_ = true;
  return true;
}

bool EpisodeCapture::on_camera_frame(const CanFrame& f, uint64_t now) {
  if (!waiting_ || image_ok_) {
    const IsoTpFrameType type = isotp_frame_type(f);
    if (image_received_ && (type == IsoTpFrameType::kFirst || type == IsoTpFrameType::kSingle))
      second_answer();  // another transfer after this capture's frame was whole
    return false;
  }
  const bool was_busy = image_rx_.busy();
  IsoTpReply reply;
  const IsoTpStatus s = image_rx_.on_frame(f, now, &reply);
  if (reply.valid) master_->send(&reply.frame, 1);
  switch (s) {
    case IsoTpStatus::kComplete:
      if (image_rx_.size() == kCameraImageBytes)
        image_ok_ = image_received_ = true;
      else
        master_->raise(Fault::kImageError, kCameraNode);  // a message, but not one frame
      return true;
    case IsoTpStatus::kInProgress:
    case IsoTpStatus::kIgnored:
    case IsoTpStatus::kIdle:
      return true;
    case IsoTpStatus::kUnexpected:
      // A consecutive frame of an earlier, abandoned transfer: nothing of ours broke.
      if (!was_busy) return false;
      master_->raise(Fault::kImageError, kCameraNode);
      return true;
    default:  // sequence error, truncated, oversized (OVFLW sent), timeout
      master_->raise(Fault::kImageError, kCameraNode);
      return true;
  }
}

bool EpisodeCapture::capture(uint32_t episode, nn::Encoder* encoder, float* outcome,
                             EpisodeRecord* record) {
  late_answers_possible_ = episode == episode_ && !answered_;
  episode_ = episode;
  if (!master_->config().camera_on_bus) return capture_local(encoder, outcome, record);
  local_ = false;
  ground_truth_ok_ = false;
  image_ok_ = !master_->config().want_image;
  image_received_ = false;
  image_rx_.set_link(camera_link_for_controller(master_->profile()));  // resets it
  const CanFrame request = encode_camera_capture({episode});
  waiting_ = true;
  const bool ok =
      master_->send(&request, 1) &&
      master_->pump_until(*this, master_->bus().now_us() + master_->config().capture_timeout_us);
  waiting_ = false;
  answered_ = done();
  if (!ok) {
    master_->raise(Fault::kCaptureTimeout, kCameraNode);
    return false;
  }
  const GroundTruth& g = ground_truth_;
  if (!std::isfinite(g.ball_x) || !std::isfinite(g.ball_y) || !std::isfinite(g.distractor_x) ||
      !std::isfinite(g.distractor_y)) {
    master_->raise(Fault::kGroundTruthInvalid, kCameraNode);
    return false;
  }
  const FinalPositions final_positions{.ball_x = g.ball_x,
                                       .ball_y = g.ball_y,
                                       .distractor_x = g.distractor_x,
                                       .distractor_y = g.distractor_y};
  if (!episode_outcome(final_positions, encoder, image_, outcome)) {
    master_->raise(Fault::kEncoderFailed, kCameraNode);
    return false;
  }
  record->ball[0] = static_cast<float>(g.ball_x);
  record->ball[1] = static_cast<float>(g.ball_y);
  record->distractor[0] = static_cast<float>(g.distractor_x);
  record->distractor[1] = static_cast<float>(g.distractor_y);
  record->grasped = g.ball_grasped;
  return true;
}

bool EpisodeCapture::capture_local(nn::Encoder* encoder, float* outcome, EpisodeRecord* record) {
  const ControllerConfig& config = master_->config();
  if (source_ == nullptr || encoder == nullptr) {  // Controller::init refuses both
    master_->raise(Fault::kCameraFailed, 0);
    return false;
  }
  local_ = true;
  ground_truth_ok_ = true;  // none to wait for
  image_ok_ = false;
  source_->request_frame(config.frame_settle_us);
  // The bus is pumped meanwhile (heartbeats checked); poll() asks the source on every wake-up.
  const uint64_t deadline = master_->bus().now_us() + config.frame_settle_us + config.frame_timeout_us;
  const bool ok = master_->pump_until(*this, deadline);
  local_ = false;
  if (!ok) {
    master_->raise(Fault::kCameraFailed, 0);  // no fresh frame in time (or the cause raised first)
    return false;
  }
  const double unknown = std::numeric_limits<double>::quiet_NaN();
  const FinalPositions none{.ball_x = unknown, .ball_y = unknown, .distractor_x = unknown,
                            .distractor_y = unknown};
  if (!episode_outcome(none, encoder, image_, outcome)) {
    master_->raise(Fault::kEncoderFailed, 0);
    return false;
  }
  record->ball[0] = record->ball[1] = static_cast<float>(unknown);
  record->distractor[0] = record->distractor[1] = static_cast<float>(unknown);
  record->grasped = false;
  return true;
}

}  // namespace curio::app
