// One episode's attempts and retries: scene reset, 50 SYNC cycles, the capture (retried alone
// on a capture fault); after any other fault the arm is brought back and the episode replayed.
#pragma once
#include <cstdint>

#include "firmware/app/canopen_master.hpp"
#include "firmware/app/control_cycle.hpp"
#include "firmware/app/episode_capture.hpp"

namespace curio::nn {
class Encoder;
}

namespace curio::app {

class EpisodeAttempts {
 public:
  EpisodeAttempts(CanOpenMaster* master, ControlCycle* cycle, EpisodeCapture* capture)
      : master_(master), cycle_(cycle), capture_(capture) {}

  // Episode `episode` with θ, up to max_attempts (record->attempts counts them). true: one
  // attempt completed without a fault; its outcome and final positions are filled in.
  // false: every attempt hit a fault, a fatal one (is_fatal) ended them, or the arm could not
  // be brought back; *arm_ready is then cleared unless the arm is known to be up.
  bool run(uint32_t episode, const float theta[kThetaDim], nn::Encoder* encoder, float* outcome,
           EpisodeRecord* record, bool* arm_ready);

 private:
  bool run_attempt(uint32_t episode, const float theta[kThetaDim], nn::Encoder* encoder,
                   float* outcome, EpisodeRecord* record);

  CanOpenMaster* master_;
  ControlCycle* cycle_;
  EpisodeCapture* capture_;
};

}  // namespace curio::app
