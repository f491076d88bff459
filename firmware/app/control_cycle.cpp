// One SYNC cycle: joint targets out (RPDO1 + SYNC), feedback in (TPDO1) and checked.
#include "firmware/app/control_cycle.hpp"

#include <cmath>

#include "firmware/app/joint_target.hpp"
#include "firmware/protocol/cia402.hpp"

namespace curio::app {

using hal::CanFrame;
using namespace protocol;
using cia402::DriveState;

static_assert(kJoints == kJointNodes, "one CiA 402 node per joint");
static_assert(kJointLimitCounts > 0 && kJointLimitCounts < INT32_MAX / 2, "joint range fits");

namespace {

// 2π in counts, for the following error of joints whose angle wraps at ±π.
constexpr double kTwoPiCounts = 2.0 * kPi * kCountsPerRad;

}  // namespace

bool ControlCycle::done() const {
  return feedback_mask_ == (1u << kJoints) - 1;
}

bool ControlCycle::on_feedback(const JointFeedback& fb) {
  const auto bit = static_cast<uint8_t>(1u << (fb.node - kFirstJointNode));
  if ((feedback_mask_ & bit) != 0) return false;  // duplicate
  feedback_[fb.node - kFirstJointNode] = fb;
  feedback_mask_ = static_cast<uint8_t>(feedback_mask_ | bit);
  return true;
}

bool ControlCycle::run(int t, const float theta[kThetaDim]) {
  PeriodPacer* const pacer = master_->pacer();
  if (pacer != nullptr) pacer->period_begin(t);
  const bool ok = step(t, theta);
  if (pacer != nullptr) pacer->period_end(t);
  return ok;
}

bool ControlCycle::step(int t, const float theta[kThetaDim]) {
  CycleProbe* const probe = master_->probe();
  const ControllerConfig& config = master_->config();
  if (probe != nullptr) probe->cycle_work_begin();
  float commands[kJoints];
  primitive_.commands(theta, t, commands);
  // The drives' speed limit (0x607F) as a step per period: a target further from the last one
  // (the start pose at t = 0) is moved towards it by that much, so the arm can follow and the
  // following error check holds. At the default (π per period) no exploration's step is
  // limited (docs/hil.md).
  const int64_t max_step = static_cast<int64_t>(config.drives.max_speed) * kControlPeriodMs / 1000;
  for (int j = 0; j < kJoints; ++j) {
    int32_t counts = 0;
    if (command_to_counts(commands[j], &counts) != CodecStatus::kOk ||
        !within_joint_limits(counts, config.joint_limit_counts)) {
      // Not sent: the joints keep the last safe targets; the attempt ends here.
      master_->raise(Fault::kJointLimit, node_id(j));
      if (probe != nullptr) probe->cycle_work_end();
      return false;
    }
    const int64_t from = t == 0 ? 0 : targets_[j];
    const int64_t step = static_cast<int64_t>(counts) - from;
    if (step > max_step || step < -max_step) {
      counts = static_cast<int32_t>(from + (step > 0 ? max_step : -max_step));
      ++master_->counters().limited_targets;
    }
    targets_[j] = counts;
  }
  CanFrame frames[kJoints + 1];
  for (int j = 0; j < kJoints; ++j)
    frames[j] = encode_joint_command({node_id(j), cia402::kCwEnableOperation, targets_[j]});
  frames[kJoints] = sync_.next();
  feedback_mask_ = 0;
  bool ok = master_->send(frames, kJoints + 1);
  if (ok) {
    ok = master_->pump_until(*this, master_->bus().now_us() + config.feedback_timeout_us);
    if (!ok) {
      for (int j = 0; j < kJoints; ++j)
        if ((feedback_mask_ & (1u << j)) == 0) master_->raise(Fault::kFeedbackTimeout, node_id(j));
    }
  }
  if (ok) {
    for (int j = 0; j < kJoints && ok; ++j) {
      const JointFeedback& fb = feedback_[j];
      if (cia402::decode_state(fb.statusword) != DriveState::kOperationEnabled) {
        master_->raise(Fault::kDriveFault, fb.node);
        ok = false;
        break;
      }
      const double error = std::remainder(
          static_cast<double>(static_cast<int64_t>(fb.actual_counts) - targets_[j]), kTwoPiCounts);
      if (std::fabs(error) > static_cast<double>(config.following_error_counts)) {
        master_->raise(Fault::kFollowingError, fb.node);
        ok = false;
      }
    }
  }
  if (ok) ++master_->counters().sync_cycles;
  if (probe != nullptr) probe->cycle_work_end();
  return ok;
}

}  // namespace curio::app
