// The controller's status codes (what its calls return) and fault kinds (why an attempt ended).
#pragma once
#include <cstddef>
#include <cstdint>

namespace curio::app {

enum class AppStatus : uint8_t {
  kOk = 0,
  kNotInitialised,   // init() not called or failed
  kInvalidArgument,  // null bus/explorer, bad config
  kArmNotReady,      // start_arm() did not reach "all joints operation enabled"
  kEpisodeFailed,    // every attempt of the episode hit a fault; nothing archived
  kDone,             // the explorer has observed all its episodes
  kExplorerError,    // propose/observe refused (see explorer counters)
  kJournalError,     // the episode was archived but its journal append failed (journal.hpp)
};
const char* to_string(AppStatus s);

enum class Fault : uint8_t {
  kNone = 0,
  kSdoTimeout,          // no SDO answer in time
  kSdoAbort,            // a node refused an SDO transfer
  kBootTimeout,         // a node did not boot / become operational in time
  kHeartbeatLost,       // no heartbeat from a node for heartbeat_timeout_us
  kNodeState,           // a heartbeat reports a node not operational (stopped, rebooted)
  kEmergency,           // an EMCY with an error code
  kDriveFault,          // a statusword not "operation enabled" (fault, disabled, quick stop)
  kFeedbackTimeout,     // not all 7 TPDO1 after a SYNC in time
  kFollowingError,      // actual position differs from the target beyond tolerance
  kJointLimit,          // a computed target outside the joint limits (never sent)
  kBusOff,              // our controller is bus-off or the bus is down
  kSendFailed,          // the bus refused a frame (queue full, deadline)
  kCaptureTimeout,      // ground truth or camera frame incomplete in time
  kImageError,          // ISO-TP: sequence error, truncated, oversized, unexpected
  kGroundTruthInvalid,  // non-finite values
  kEncoderFailed,       // the encoder refused the frame
  kOtherMaster,         // a master's frame (NMT, SYNC, RPDO, SDO request, capture) we did not send
  kDuplicateNode,       // two answers to one SDO request: two nodes with one id (two arms)
  kStopRequested,       // the host asked the controller to stop (SIGTERM, SIGINT, SIGHUP)
  kMasterHeartbeatMissed,  // a drive missed the controller's heartbeat (EMCY 0x8130) and stopped
  kConfigRejected,      // a drive refused a configuration value or did not keep it (read back)
  kWrongDevice,         // a node's device type (0x1000) is not what the controller drives
  kCameraFailed,        // the local camera (FrameSource) stalled, ended or gave a wrong frame
  kDuplicateCapture,    // two answers to one capture: a second camera, or a forged ground truth
  kCount
};
inline constexpr size_t kFaultKinds = static_cast<size_t>(Fault::kCount);
const char* to_string(Fault f);

// The bus is shared with another master or another arm, whose frames change the scene and the
// answers: the arm is not ours to drive, or to stop.
constexpr bool shares_bus(Fault f) {
  return f == Fault::kOtherMaster || f == Fault::kDuplicateNode;
}

// Faults that no recovery or replay can cure (a shared bus, drives that refuse the
// configuration or are not the devices the controller drives), and a stop the host asked
// for: the run stops at once (no replay), after a controlled stop of the arm where it is ours.
constexpr bool is_fatal(Fault f) {
  return shares_bus(f) || f == Fault::kDuplicateCapture || f == Fault::kStopRequested ||
         f == Fault::kConfigRejected ||
         f == Fault::kWrongDevice;
}

}  // namespace curio::app
