// Arm start-up and recovery: NMT, SDO configuration, CiA 402 enable.
#include "firmware/app/arm_bringup.hpp"

#include "firmware/app/drive_config.hpp"
#include "firmware/protocol/arm_objects.hpp"
#include "firmware/protocol/cia402.hpp"

namespace curio::app {

using namespace protocol;
using cia402::DriveState;

namespace {

bool all_joints_write(CanOpenMaster& master, uint16_t index, uint8_t sub, uint32_t value,
                      uint8_t size) {
  return master.sdo().transfer_all_joints(SdoKind::kDownloadRequest, index, sub, value, size);
}

bool all_joints_read_statusword(CanOpenMaster& master) {
  return master.sdo().transfer_all_joints(SdoKind::kUploadRequest, cia402::kStatusword, 0, 0, 0);
}

DriveState joint_state(CanOpenMaster& master, int j) {
  return cia402::decode_state(static_cast<uint16_t>(master.sdo().joint_value(j)));
}

bool camera_write(CanOpenMaster& master, uint16_t index, uint8_t sub, uint32_t value,
                  uint8_t size) {
  return master.sdo().transfer(kCameraNode, SdoKind::kDownloadRequest, index, sub, value, size);
}

bool enable_joints(CanOpenMaster& master) {
  // Out of fault (rising edge of bit 7) or quick stop active (disable voltage first) where
  // needed, then shutdown → switch on → enable.
  if (!all_joints_read_statusword(master)) return false;
  bool any_fault = false;
  bool any_quick_stop = false;
  for (int j = 0; j < kJointNodes; ++j) {
    any_fault = any_fault || joint_state(master, j) == DriveState::kFault;
    any_quick_stop = any_quick_stop || joint_state(master, j) == DriveState::kQuickStopActive;
  }
  if ((any_fault || any_quick_stop) &&
      !all_joints_write(master, cia402::kControlword, 0, cia402::kCwDisableVoltage, 2))
    return false;
  if (any_fault && !all_joints_write(master, cia402::kControlword, 0, cia402::kCwFaultReset, 2))
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

bool bring_up_arm(CanOpenMaster& master, bool reset_nodes, NodeIdentity* identities) {
  const ControllerConfig& config = master.config();
  HeartbeatConsumer& heartbeats = master.heartbeats();
  NmtMaster& nmt = master.nmt();
  ++master.counters().arm_bringups;
  heartbeats.stop_watch();
  master.set_drives_watch_us(false);  // until configure_drives has armed their consumers
  // Our heartbeat first: the drives' consumer (0x1016, configured below) arms on it.
  const DriveSafetyConfig& drives = config.drives;
  if (!master.heartbeat_producer().active())
    master.heartbeat_producer().start(drives.master_node, drives.master_heartbeat_ms,
                                      master.bus().now_us());
  if (reset_nodes) {
    // Reset node, to each node by id: every node (and the simulated world) starts afresh and
    // sends boot-up.
    heartbeats.forget();
    heartbeats.expect_boot_up(true);
    const bool booted = nmt.send(NmtCommand::kResetNode) && nmt.await(true, NmtState::kBootUp);
    heartbeats.expect_boot_up(false);
    if (!booted) return false;
  }
  // Pre-operational (SDO works there, not in "stopped"; PDOs pause); the nodes' identity (at
  // start), then the configuration: heartbeats, the drives' safety objects, CSP mode,
  // interpolation period 10 ms, camera capture content.
  if (!nmt.send(NmtCommand::kEnterPreOperational)) return false;
  if (identities != nullptr && !read_node_identities(master, identities)) return false;
  if (!all_joints_write(master, od::kHeartbeatProducerTime, 0, config.heartbeat_producer_ms, 2) ||
      !configure_drives(master))
    return false;
  master.set_drives_watch_us(true);
  // Our heartbeat at once: the consumers just configured watch from it on, before the drives
  // are enabled (with the period's wait, a controller killed in the first 100 ms of a run left
  // the drives enabled and unwatched: app_drive_watchdog saw it about once in 20 kills).
  master.heartbeat_producer().due_now(master.bus().now_us());
  if (!all_joints_write(master, cia402::kModesOfOperation, 0,
                        static_cast<uint8_t>(cia402::kModeCyclicSynchronousPosition), 1) ||
      !all_joints_write(master, cia402::kInterpolationTimePeriod, od::kInterpolationPeriodValueSub,
                        kControlPeriodMs, 1) ||
      !all_joints_write(master, cia402::kInterpolationTimePeriod, od::kInterpolationPeriodIndexSub,
                        static_cast<uint8_t>(-3 & 0xFF), 1))
    return false;
  const uint8_t content =
      static_cast<uint8_t>(od::kCaptureGroundTruth | (config.want_image ? od::kCaptureImage : 0));
  if (config.camera_on_bus &&
      (!camera_write(master, od::kHeartbeatProducerTime, 0, config.heartbeat_producer_ms, 2) ||
       !camera_write(master, od::kCaptureContent, 0, content, 1)))
    return false;
  // NMT start; wait until every node's heartbeat says operational.
  heartbeats.forget();
  if (!nmt.send(NmtCommand::kStart) || !nmt.await(false, NmtState::kOperational)) return false;
  heartbeats.start_watch(master.bus().now_us());
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
    if (bring_up_arm(master, false, nullptr)) return true;
  }
  return false;
}

}  // namespace curio::app
