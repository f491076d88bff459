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
  return s;
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
