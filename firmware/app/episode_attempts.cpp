// One episode's attempts: cycles and capture, capture retries, replays after a fault.
#include "firmware/app/episode_attempts.hpp"

#include "firmware/app/arm_bringup.hpp"
#include "firmware/protocol/arm_objects.hpp"

namespace curio::app {

using namespace protocol;

bool EpisodeAttempts::run_attempt(uint32_t episode, const float theta[kThetaDim],
                                  nn::Encoder* encoder, float* outcome, EpisodeRecord* record) {
  master_->clear_fault();
  master_->begin_attempt();
  // Scene reset (the same episode number again: the camera node replays the episode).
  // No camera node (a camera on the controller's computer): no scene to reset.
  if (master_->config().camera_on_bus &&
      !master_->sdo().transfer(kCameraNode, SdoKind::kDownloadRequest, od::kEpisodeControl,
                               od::kEpisodeStartSub, episode, 4))
    return false;
  for (int t = 0; t < kStepsPerEpisode; ++t)
    if (!cycle_->run(t, theta)) return false;
  for (int c = 0;; ++c) {
    if (capture_->capture(episode, encoder, outcome, record)) return true;
    const Fault fault = master_->fault();
    const bool capture_fault = fault == Fault::kCaptureTimeout || fault == Fault::kImageError;
    if (!capture_fault || c + 1 >= master_->config().capture_attempts) return false;
    ++master_->counters().capture_retries;
    master_->clear_fault();  // counted; the capture is attempted again
  }
}

bool EpisodeAttempts::run(uint32_t episode, const float theta[kThetaDim], nn::Encoder* encoder,
                          float* outcome, EpisodeRecord* record, bool* arm_ready) {
  ControllerCounters& counters = master_->counters();
  const int max_attempts = master_->config().max_attempts;
  bool ok = false;
  for (int attempt = 1; attempt <= max_attempts; ++attempt) {
    ++counters.attempts;
    if (attempt > 1) ++counters.replays;
    record->attempts = attempt;
    ok = run_attempt(episode, theta, encoder, outcome, record);
    if (ok) break;
    // Hold: nothing more goes to the joints. Bring the arm back, then replay the episode;
    // not when another master or arm shares the bus (no replay can cure that).
    if (master_->fatal_fault() != Fault::kNone) {
      *arm_ready = false;
      break;
    }
    // A local camera that stalled, ended or gave a wrong frame gives no more frames: the run
    // stops (the arm is up; the caller names the cause).
    if (master_->fault() == Fault::kCameraFailed) break;
    if (attempt == max_attempts) break;
    if (!recover_arm(*master_)) {
      *arm_ready = false;
      break;
    }
  }
  if (!ok) *arm_ready = *arm_ready && master_->fault() == Fault::kNone;
  return ok;
}

}  // namespace curio::app
