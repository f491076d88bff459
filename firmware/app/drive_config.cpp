// The drives' safety configuration: written, read back, refused by name.
#include "firmware/app/drive_config.hpp"

#include "firmware/app/canopen_master.hpp"
#include "firmware/protocol/cia402.hpp"

namespace curio::app {

using namespace protocol;

namespace {

using namespace protocol::od;  // the CiA 301/402 objects (arm_objects.hpp)

// A value of `size` bytes as the SDO carries it (the upper bytes of a short read are zero).
constexpr uint32_t masked(uint32_t v, uint8_t size) {
  return size >= 4 ? v : v & ((1u << (8u * size)) - 1u);
}

uint32_t u32_of(int32_t v) {
  return static_cast<uint32_t>(v);
}
uint32_t u32_of_i16(int16_t v) {
  return static_cast<uint32_t>(static_cast<uint16_t>(v));
}

void rejected(CanOpenMaster& master, int j, const DriveObject& o, uint32_t read, uint32_t abort) {
  ControllerCounters& c = master.counters();
  c.config_node = node_id(j);
  c.config_index = o.index;
  c.config_sub = o.sub;
  c.config_written = o.value;
  c.config_read = read;
  c.config_abort = abort;
  master.clear_fault();  // the refusal is the cause, not the SDO abort that carried it
  master.raise(Fault::kConfigRejected, node_id(j));
}

}  // namespace

static_assert(kDriveObjects == 11, "drive_objects() fills every entry");

void drive_objects(const ControllerConfig& config, DriveObject out[kDriveObjects]) {
  const DriveSafetyConfig& d = config.drives;
  size_t n = 0;
  out[n++] = {kConsumerHeartbeatTime, 1, 4,
              consumer_heartbeat_entry(d.master_node, d.consumer_time_ms)};
  out[n++] = {kAbortConnectionOption, 0, 2, u32_of_i16(d.abort_connection_option)};
  out[n++] = {kQuickStopOptionCode, 0, 2, u32_of_i16(d.quick_stop_option)};
  out[n++] = {kFaultReactionOptionCode, 0, 2, u32_of_i16(d.fault_reaction_option)};
  out[n++] = {kQuickStopDeceleration, 0, 4, d.quick_stop_decel};
  out[n++] = {kSoftwarePositionLimit, kPositionLimitMinSub, 4, u32_of(-config.joint_limit_counts)};
  out[n++] = {kSoftwarePositionLimit, kPositionLimitMaxSub, 4, u32_of(config.joint_limit_counts)};
  out[n++] = {kMaxProfileVelocity, 0, 4, d.max_speed};
  out[n++] = {kMaxMotorSpeed, 0, 4, d.max_speed};
  out[n++] = {kFollowingErrorWindow, 0, 4, d.following_error_window};
  out[n++] = {kFollowingErrorTimeOut, 0, 2, d.following_error_time_ms};
}

bool configure_drives(CanOpenMaster& master) {
  DriveObject objects[kDriveObjects];
  drive_objects(master.config(), objects);
  SdoClient& sdo = master.sdo();
  for (const DriveObject& o : objects) {
    uint8_t answered = 0;
    // Written to all joints in one batch; a joint that does not answer is a timeout fault.
    sdo.transfer_all_joints(SdoKind::kDownloadRequest, o.index, o.sub, o.value, o.size, &answered);
    for (int j = 0; j < kJointNodes; ++j) {
      if ((answered & (1u << j)) != 0) continue;
      if (sdo.joint_aborted(j)) {
        rejected(master, j, o, 0, sdo.joint_value(j));
      } else {
        master.raise(Fault::kSdoTimeout, node_id(j));
      }
      return false;
    }
    sdo.transfer_all_joints(SdoKind::kUploadRequest, o.index, o.sub, 0, 0, &answered);
    for (int j = 0; j < kJointNodes; ++j) {
      if ((answered & (1u << j)) == 0) {
        if (sdo.joint_aborted(j)) {
          rejected(master, j, o, 0, sdo.joint_value(j));
        } else {
          master.raise(Fault::kSdoTimeout, node_id(j));
        }
        return false;
      }
      const uint32_t read = masked(sdo.joint_value(j), o.size);
      if (read != masked(o.value, o.size)) {
        rejected(master, j, o, read, 0);
        return false;
      }
    }
  }
  return master.fault() == Fault::kNone;
}

void release_drives(CanOpenMaster& master) {
  uint8_t answered = 0;
  master.sdo().transfer_all_joints(SdoKind::kDownloadRequest, kConsumerHeartbeatTime, 1, 0, 4,
                                   &answered);
}

}  // namespace curio::app
