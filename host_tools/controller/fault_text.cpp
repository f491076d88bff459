#include "host_tools/controller/fault_text.hpp"

#include <cstdio>

namespace curio::app::host {

std::string fault_summary(const ControllerCounters& c) {
  std::string s;
  for (size_t i = 1; i < kFaultKinds; ++i) {
    if (c.faults[i] == 0) continue;
    s += std::string(to_string(static_cast<Fault>(i))) + " " + std::to_string(c.faults[i]) + "; ";
  }
  if (s.empty()) return "no faults";
  s += "last: " + std::string(to_string(c.last_fault)) + " (node " +
       std::to_string(c.last_fault_node) + ")";
  if (c.last_emcy_code != 0) s += "; last EMCY " + emcy_text(c.last_emcy_code, c.last_emcy_node);
  return s;
}

std::string emcy_text(uint16_t code, uint8_t node) {
  char buf[160];
  const char* meaning = code == kEmcyHeartbeatError       ? "the drive missed the controller's heartbeat"
                        : code == kEmcyFollowingErrorCode ? "following error"
                        : code == 0x8612                  ? "target outside the joint's range"
                                                          : "";
  std::snprintf(buf, sizeof buf, "0x%04X from node %u%s%s%s", code, node, *meaning ? " (" : "",
                meaning, *meaning ? ")" : "");
  return buf;
}

std::string signal_name(int signo) {
  switch (signo) {
    case 1:
      return "SIGHUP";
    case 2:
      return "SIGINT";
    case 15:
      return "SIGTERM";
    default:
      return "signal " + std::to_string(signo);
  }
}

std::string stop_report_text(const StopReport& r) {
  if (!r.sent) return std::string("controlled stop not sent: ") + r.skipped;
  const auto joints = [](uint8_t mask) {
    std::string s;
    for (int j = 0; j < protocol::kJointNodes; ++j) {
      if ((mask & (1u << j)) == 0) continue;
      if (!s.empty()) s += ',';
      s += std::to_string(j + 1);
    }
    return s.empty() ? std::string("none") : s;
  };
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.3f s", r.standstill_us / 1e6);
  if (r.complete())
    return std::string("controlled stop: quick stop to joints 1-7, all stood still after ") + buf +
           ", then disabled";
  return "controlled stop INCOMPLETE: quick stop taken by joints " + joints(r.quick_stopped) +
         ", standstill confirmed by " + joints(r.standstill) + ", disabled: " +
         joints(r.disabled) + " (check the drives: the others did not answer)";
}

std::string fatal_fault_text(const ControllerCounters& c, Fault fatal) {
  const std::string node = std::to_string(c.last_fault_node);
  if (fatal == Fault::kOtherMaster)
    return "another master is on this bus: " + std::to_string(c.other_master_frames) +
           " NMT/SYNC/RPDO/SDO-request/capture frames this controller did not send (is a "
           "second curio-controller running on it?); its frames change the arm's scene, so "
           "this run cannot continue";
  if (fatal == Fault::kDuplicateNode)
    return "two nodes answer as node " + node + " (" + std::to_string(c.duplicate_answers) +
           " duplicate SDO answers): a second arm (another curio-sim serve?) is on this bus";
  if (fatal == Fault::kDuplicateCapture)
    return "two answers to one capture of the camera (node " + node +
           "): a second camera, or another process forging ground truth (0x2A0) or camera "
           "frames, is on this bus; the scene it reports cannot be trusted, so this run "
           "cannot continue";
  char object[64];
  std::snprintf(object, sizeof object, "0x%04X.%u", c.config_index, c.config_sub);
  char value[96];
  if (fatal == Fault::kConfigRejected) {
    if (c.config_abort != 0)
      std::snprintf(value, sizeof value, "%u (0x%08X): SDO abort 0x%08X", c.config_written,
                    c.config_written, c.config_abort);
    else
      std::snprintf(value, sizeof value, "%u (0x%08X), but it reads back %u (0x%08X)",
                    c.config_written, c.config_written, c.config_read, c.config_read);
    return "drive node " + std::to_string(c.config_node) + " refused its configuration: object " +
           object + " = " + value + " (docs/hil.md lists what each object is for)";
  }
  if (fatal == Fault::kWrongDevice) {
    std::snprintf(value, sizeof value, "0x%08X", c.config_read);
    return "node " + std::to_string(c.config_node) + "'s device type (0x1000) is " + value +
           (c.config_node == protocol::kCameraNode
                ? ", not a camera device of no standard profile (0x....0000)"
                : ", not a CiA 402 drive (0x....0192)") +
           ": the controller does not drive it";
  }
  if (fatal == Fault::kStopRequested) return "stopped on request";
  return to_string(fatal);
}

std::string bring_up_failure_text(const ControllerCounters& c, AppStatus s) {
  std::string text =
      std::string("the arm did not come up: ") + to_string(s) + " (" + fault_summary(c) + "); ";
  if (c.state_regressions == 0) return text + "is `curio-sim serve` running on this bus?";
  const std::string node = std::to_string(c.last_regression_node);
  return text + "node " + node +
         "'s heartbeat said operational, then another state, with no reset or NMT command "
         "between: two nodes answer as node " + node +
         " (a second arm, another curio-sim serve, on this bus?), or the node left operational "
         "on an error or restarted";
}

namespace {

std::string seconds_text(uint64_t us) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g s", static_cast<double>(us) / 1e6);
  return buf;
}

}  // namespace

std::string episode_failure_text(const Controller& controller, AppStatus s,
                                 const ControllerConfig& config) {
  const Fault fatal = controller.fatal_fault();
  if (fatal != Fault::kNone) return fatal_fault_text(controller.counters(), fatal);
  std::string text =
      std::string(to_string(s)) + " (" + fault_summary(controller.counters()) + "); ";
  // A camera on this computer that failed gives no more frames: no replay (the caller names why).
  if (controller.counters().last_fault == Fault::kCameraFailed)
    return text + "the camera (--camera) gives no fresh frame, so nothing was archived from it";
  // Every attempt ran (the arm came back before each): the faults recur, the arm is there.
  if (s == AppStatus::kEpisodeFailed && controller.last_episode().attempts >= config.max_attempts)
    return text + "each of its " + std::to_string(config.max_attempts) +
           " attempts (--max-attempts) hit a fault, though the arm came back between them";
  return text + "the arm did not come back within the hold time (" +
         seconds_text(config.recovery_timeout_us) + ", --hold-time)";
}

}  // namespace curio::app::host
