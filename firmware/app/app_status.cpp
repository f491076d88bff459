// Names of the controller's status codes and fault kinds (logs, result files).
#include "firmware/app/app_status.hpp"

namespace curio::app {

const char* to_string(AppStatus s) {
  switch (s) {
    case AppStatus::kOk:
      return "ok";
    case AppStatus::kNotInitialised:
      return "not initialised";
    case AppStatus::kInvalidArgument:
      return "invalid argument";
    case AppStatus::kArmNotReady:
      return "arm not ready";
    case AppStatus::kEpisodeFailed:
      return "episode failed (all attempts hit a fault)";
    case AppStatus::kDone:
      return "done";
    case AppStatus::kExplorerError:
      return "explorer error";
    case AppStatus::kJournalError:
      return "journal append failed";
  }
  return "?";
}

const char* to_string(Fault f) {
  switch (f) {
    case Fault::kNone:
      return "none";
    case Fault::kSdoTimeout:
      return "sdo_timeout";
    case Fault::kSdoAbort:
      return "sdo_abort";
    case Fault::kBootTimeout:
      return "boot_timeout";
    case Fault::kHeartbeatLost:
      return "heartbeat_lost";
    case Fault::kNodeState:
      return "node_state";
    case Fault::kEmergency:
      return "emergency";
    case Fault::kDriveFault:
      return "drive_fault";
    case Fault::kFeedbackTimeout:
      return "feedback_timeout";
    case Fault::kFollowingError:
      return "following_error";
    case Fault::kJointLimit:
      return "joint_limit";
    case Fault::kBusOff:
      return "bus_off";
    case Fault::kSendFailed:
      return "send_failed";
    case Fault::kCaptureTimeout:
      return "capture_timeout";
    case Fault::kImageError:
      return "image_error";
    case Fault::kGroundTruthInvalid:
      return "ground_truth_invalid";
    case Fault::kEncoderFailed:
      return "encoder_failed";
    case Fault::kOtherMaster:
      return "other_master";
    case Fault::kDuplicateNode:
      return "duplicate_node";
    case Fault::kStopRequested:
      return "stop_requested";
    case Fault::kMasterHeartbeatMissed:
      return "master_heartbeat_missed";
    case Fault::kConfigRejected:
      return "config_rejected";
    case Fault::kWrongDevice:
      return "wrong_device";
    case Fault::kCameraFailed:
      return "camera_failed";
    case Fault::kDuplicateCapture:
      return "duplicate_capture";
    case Fault::kCount:
      break;
  }
  return "?";
}

}  // namespace curio::app
