// Arm start-up and recovery: NMT, SDO configuration, CiA 402 enable.
#include "firmware/app/arm_bringup.hpp"

#include "firmware/protocol/arm_objects.hpp"
#include "firmware/protocol/cia402.hpp"

namespace curio::app {

using namespace protocol;
using cia402::DriveState;

namespace {

bool all_joints_write(CanOpenMaster& master, uint16_t index, uint8_t sub, uint32_t value,
                      uint8_t size) {
  return master.sdo_all_joints(SdoKind::kDownloadRequest, index, sub, value, size);
}

bool all_joints_read_statusword(CanOpenMaster& master) {
  return master.sdo_all_joints(SdoKind::kUploadRequest, cia402::kStatusword, 0, 0, 0);
}

DriveState joint_state(const CanOpenMaster& master, int j) {
  return cia402::decode_state(static_cast<uint16_t>(master.joint_sdo_value(j)));
}

bool enable_joints(CanOpenMaster& master) {
  // Fault reset where needed (rising edge of bit 7), then shutdown → switch on → enable.
  if (!all_joints_read_statusword(master)) return false;
  bool any_fault = false;
  for (int j = 0; j < kJointNodes; ++j)
    any_fault = any_fault || joint_state(master, j) == DriveState::kFault;
  if (any_fault &&
      (!all_joints_write(master, cia402::kControlword, 0, cia402::kCwDisableVoltage, 2) ||
       !all_joints_write(master, cia402::kControlword, 0, cia402::kCwFaultReset, 2)))
    return false;
  if (!all_joints_write(master, cia402::kControlword, 0, cia402::kCwShutdown, 2) ||
      !all_joints_write(master, cia402::kControlword, 0, cia402::kCwSwitchOn, 2) ||
      !all_joints_write(master, cia402::kControlword, 0, cia402::kCwEnableOperation, 2) ||
      !all_joints_read_statusword(master))
    return false;
  for (int j = 0; j < kJointNodes; ++j) {
    if (joint_state(master, j) != DriveState::kOperationEnabled) {
      master.raise(Fault::kDriveFault, node_id(j));
      return false;
    }
  }
  return true;
}

}  // namespace

bool bring_up_arm(CanOpenMaster& master, bool reset_nodes) {
  const ControllerConfig& config = master.config();
  ++master.counters().arm_bringups;
  master.stop_heartbeat_watch();
  if (reset_nodes) {
    // Reset node: every node (and the simulated world) starts afresh and sends boot-up.
    master.forget_heartbeats();
    master.expect_boot_up(true);
    const bool booted =
        master.send_nmt(NmtCommand::kResetNode) && master.await_nmt(true, NmtState::kBootUp);
    master.expect_boot_up(false);
    if (!booted) return false;
  }
  // Pre-operational (SDO works there, not in "stopped"; PDOs pause), then the configuration:
  // heartbeats, CSP mode, interpolation period 10 ms, camera capture content.
  if (!master.send_nmt(NmtCommand::kEnterPreOperational)) return false;
  if (!all_joints_write(master, od::kHeartbeatProducerTime, 0, config.heartbeat_producer_ms, 2) ||
      !all_joints_write(master, cia402::kModesOfOperation, 0,
                        static_cast<uint8_t>(cia402::kModeCyclicSynchronousPosition), 1) ||
      !all_joints_write(master, cia402::kInterpolationTimePeriod, od::kInterpolationPeriodValueSub,
                        kControlPeriodMs, 1) ||
      !all_joints_write(master, cia402::kInterpolationTimePeriod, od::kInterpolationPeriodIndexSub,
                        static_cast<uint8_t>(-3 & 0xFF), 1))
    return false;
  const uint8_t content =
      static_cast<uint8_t>(od::kCaptureGroundTruth | (config.want_image ? od::kCaptureImage : 0));
  if (config.camera_on_bus &&
      (!master.sdo(kCameraNode, SdoKind::kDownloadRequest, od::kHeartbeatProducerTime, 0,
                   config.heartbeat_producer_ms, 2) ||
       !master.sdo(kCameraNode, SdoKind::kDownloadRequest, od::kCaptureContent, 0, content, 1)))
    return false;
  // NMT start; wait until every node's heartbeat says operational.
  master.forget_heartbeats();
  if (!master.send_nmt(NmtCommand::kStart) || !master.await_nmt(false, NmtState::kOperational))
    return false;
  master.start_heartbeat_watch();
  return enable_joints(master);
}

bool recover_arm(CanOpenMaster& master) {
  hal::CanBus& bus = master.bus();
  const uint64_t deadline = bus.now_us() + master.config().recovery_timeout_us;
  while (bus.now_us() < deadline) {
    master.clear_fault();
    if (master.fatal_fault() != Fault::kNone) return false;  // not ours to bring back
    if (master.bus_off()) {
      // Wait for the controller to come back on the bus (frames still pass meanwhile).
      bus.wait_readable(1'000);
      continue;
    }
    if (bring_up_arm(master, false)) return true;
  }
  return false;
}

}  // namespace curio::app
