// One SYNC cycle of an episode: targets a_j(t) → counts (limit-checked) → 7 RPDO1 + SYNC in one
// batch → the 7 TPDO1 feedback checks (operation enabled, following error within tolerance).
#pragma once
#include <cstdint>

#include "firmware/app/canopen_master.hpp"
#include "firmware/app/sync_producer.hpp"
#include "firmware/explore/config.hpp"
#include "firmware/explore/motor_primitive.hpp"
#include "firmware/protocol/arm_messages.hpp"

namespace curio::app {

class ControlCycle final : public Wait {
 public:
  explicit ControlCycle(CanOpenMaster* master) : master_(master) {}

  // Step t of the episode with θ; false on a fault (raised). A target outside the joint
  // limits is never sent: the joints keep the last targets, all of which passed the check.
  // With a pacer (CanOpenMaster::pacer) the step waits for its period's start first.
  bool run(int t, const float theta[kThetaDim]);

  // The master's wait: all 7 TPDO1 of this cycle.
  bool done() const override;
  bool on_feedback(const protocol::JointFeedback& fb) override;

 private:
  bool step(int t, const float theta[kThetaDim]);  // run() without the pacing

  CanOpenMaster* master_;
  MotorPrimitive primitive_;
  // Targets of the current cycle (all within limits). A cycle that fails the limit check sends
  // nothing, so the joints hold the last targets that were sent; no copy of them is needed.
  int32_t targets_[kJoints] = {};
  uint8_t feedback_mask_ = 0;
  protocol::JointFeedback feedback_[kJoints];
  SyncProducer sync_;
};

}  // namespace curio::app
