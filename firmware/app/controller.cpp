// The controller application: its parts composed into init, start_arm, run_episode, stop_arm.
#include "firmware/app/controller.hpp"

#include "firmware/app/arm_bringup.hpp"
#include "firmware/app/controlled_stop.hpp"
#include "firmware/explore/module_layouts.hpp"
#include "firmware/protocol/arm_objects.hpp"

namespace curio::app {

using namespace protocol;

namespace {

// What the journal keeps of an archived episode (replay feeds outcome to the explorer and
// checks kind, module, exploit and progress; ball, distractor and grasp rebuild the results).
journal::EpisodeEntry journal_entry(const EpisodeRecord& r) {
  journal::EpisodeEntry e;
  e.episode = static_cast<uint32_t>(r.episode);
  e.kind = static_cast<uint8_t>(r.kind);
  e.module = static_cast<int8_t>(r.module);
  e.exploit = r.exploit;
  e.grasped = r.grasped;
  e.attempts = static_cast<uint8_t>(r.attempts > 255 ? 255 : r.attempts);
  e.outcome_dim = static_cast<uint8_t>(r.outcome_dim);
  e.ball[0] = r.ball[0];
  e.ball[1] = r.ball[1];
  e.distractor[0] = r.distractor[0];
  e.distractor[1] = r.distractor[1];
  e.progress = r.progress;
  for (int i = 0; i < r.outcome_dim; ++i) e.outcome[i] = r.outcome[i];
  return e;
}

}  // namespace

static_assert(sizeof(Controller) <= 21 * 1024,
              "controller state (with one camera frame) fits 21 KB of RAM");

Controller::Controller()
    : master_(&config_, &counters_),
      cycle_(&master_),
      capture_(&master_),
      attempts_(&master_, &cycle_, &capture_) {}

AppStatus Controller::init(hal::CanBus* bus, Explorer* explorer, const ControllerConfig& config,
                           nn::Encoder* encoder) {
  initialised_ = false;
  arm_ready_ = false;
  if (bus == nullptr || explorer == nullptr || !explorer->initialised())
    return AppStatus::kInvalidArgument;
  const int dim = explorer->config().outcome_dim;
  if (encoder != nullptr ? dim != kLatentDim : dim != kEfrOutcomeDim)
    return AppStatus::kInvalidArgument;
  if (config.max_attempts == 0 || config.capture_attempts == 0) return AppStatus::kInvalidArgument;
  if (config.joint_limit_counts <= 0 || config.joint_limit_counts > kJointLimitCounts)
    return AppStatus::kInvalidArgument;
  if (config.following_error_counts < 0) return AppStatus::kInvalidArgument;
  if (!drive_safety_valid(config.drives)) return AppStatus::kInvalidArgument;
  // Without a camera node there is no ground truth: engineered features cannot be measured.
  if (!config.camera_on_bus && encoder == nullptr) return AppStatus::kInvalidArgument;
  master_.set_bus(bus);
  explorer_ = explorer;
  encoder_ = encoder;
  config_ = config;
  if (encoder_ != nullptr) config_.want_image = true;
  counters_ = ControllerCounters{};
  record_ = EpisodeRecord{};
  initialised_ = true;
  return AppStatus::kOk;
}

AppStatus Controller::start_arm() {
  if (!initialised_) return AppStatus::kNotInitialised;
  master_.clear_fault();
  if (config_.listen_before_start_us > 0) {
    master_.heartbeats().expect_boot_up(true);  // boot-ups before our start are no reboots
    master_.listen(config_.listen_before_start_us);
    master_.heartbeats().expect_boot_up(false);
    if (master_.fatal_fault() != Fault::kNone) return AppStatus::kArmNotReady;
    master_.clear_fault();
  }
  for (NodeIdentity& id : identity_) id = NodeIdentity{};
  arm_ready_ = bring_up_arm(master_, config_.reset_nodes, identity_);
  return arm_ready_ ? AppStatus::kOk : AppStatus::kArmNotReady;
}

uint8_t Controller::query_physics() {
  uint32_t value = od::kPhysicsRealArm;
  if (!read_camera_object(od::kSimulatorPhysics, 0, &value)) value = od::kPhysicsRealArm;
  return static_cast<uint8_t>(value);
}

bool Controller::read_camera_object(uint16_t index, uint8_t sub, uint32_t* value) {
  if (!initialised_ || !config_.camera_on_bus) return false;  // no camera node to ask
  const Fault saved = master_.fault();
  // A refused or unanswered probe is an answer, not a fault of the run: not counted.
  const ControllerCounters before = counters_;
  master_.clear_fault();
  const bool ok =
      master_.sdo().transfer(kCameraNode, SdoKind::kUploadRequest, index, sub, 0, 0, value);
  if (!ok && !is_fatal(master_.fault())) {
    for (size_t k = 0; k < kFaultKinds; ++k) counters_.faults[k] = before.faults[k];
    counters_.fault_total = before.fault_total;
    counters_.last_fault = before.last_fault;
    counters_.last_fault_node = before.last_fault_node;
  }
  master_.restore_fault(saved);
  return ok;
}

StopReport Controller::stop_arm() {
  StopReport r;
  if (!initialised_) {
    r.skipped = "the controller was not initialised";
    return r;
  }
  r = controlled_stop(master_);
  arm_ready_ = false;
  return r;
}

AppStatus Controller::run_episode() {
  if (!initialised_) return AppStatus::kNotInitialised;
  if (explorer_->done()) return AppStatus::kDone;
  if (!arm_ready_) {
    if (master_.fatal_fault() != Fault::kNone) return AppStatus::kArmNotReady;
    master_.clear_fault();
    arm_ready_ = recover_arm(master_);
    if (!arm_ready_) return AppStatus::kArmNotReady;
  }
  float theta[kThetaDim];
  if (explorer_->propose(theta) != Status::kOk) return AppStatus::kExplorerError;
  record_ = EpisodeRecord{};
  record_.episode = explorer_->episode();
  record_.kind = explorer_->kind();
  record_.module = explorer_->module();
  record_.exploit = record_.kind == EpisodeKind::kExploit && record_.module >= 0;
  const auto episode = static_cast<uint32_t>(record_.episode);
  float outcome[kMaxOutcomeDim] = {};
  if (!attempts_.run(episode, theta, encoder_, outcome, &record_, &arm_ready_))
    // Nothing archived; the episode stays pending (propose() returns the same θ again).
    return AppStatus::kEpisodeFailed;
  if (explorer_->observe(outcome) != Status::kOk) return AppStatus::kExplorerError;
  ++counters_.episodes;
  record_.progress = record_.exploit ? explorer_->last_progress() : 0.0f;
  record_.outcome_dim = explorer_->config().outcome_dim;
  for (int i = 0; i < record_.outcome_dim; ++i) record_.outcome[i] = outcome[i];
  if (journal_ != nullptr && journal_->append(journal_entry(record_)) != journal::JournalStatus::kOk)
    return AppStatus::kJournalError;
  return AppStatus::kOk;
}

}  // namespace curio::app
