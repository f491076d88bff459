// The controlled stop: quick stop, standstill, disable.
#include "firmware/app/controlled_stop.hpp"

#include "firmware/app/canopen_master.hpp"
#include "firmware/app/drive_config.hpp"
#include "firmware/protocol/cia402.hpp"

namespace curio::app {

using namespace protocol;
using cia402::DriveState;

namespace {

constexpr uint64_t kPollUs = 10'000;  // statusword polls while the joints ramp down

bool stands_still(uint16_t statusword) {
  const DriveState s = cia402::decode_state(statusword);
  if (s == DriveState::kQuickStopActive) return (statusword & cia402::kSwTargetReached) != 0;
  // The ramp is over in these: 0x605A = 2 ends in switch on disabled, a fault reaction in fault;
  // a drive that was never enabled does not move.
  return s == DriveState::kSwitchOnDisabled || s == DriveState::kFault ||
         s == DriveState::kReadyToSwitchOn || s == DriveState::kSwitchedOn ||
         s == DriveState::kNotReadyToSwitchOn;
}

}  // namespace

StopReport controlled_stop(CanOpenMaster& master) {
  StopReport r;
  if (shares_bus(master.fatal_fault())) {
    r.skipped = "another master or arm shares the bus: its arm is not ours to stop";
    return r;
  }
  if (master.bus_off()) {
    r.skipped =
        "the bus is off or down: nothing can be sent (the drives stop by themselves on "
        "missing the controller's heartbeat)";
    return r;
  }
  const Fault cause = master.fault();
  master.set_stopping(true);
  master.heartbeats().stop_watch();
  hal::CanBus& bus = master.bus();
  SdoClient& sdo = master.sdo();
  r.sent = true;
  const uint64_t t0 = bus.now_us();
  const uint64_t deadline = t0 + master.config().stop_timeout_us;
  sdo.transfer_all_joints(SdoKind::kDownloadRequest, cia402::kControlword, 0, cia402::kCwQuickStop,
                          2, &r.quick_stopped);
  while (r.standstill != r.quick_stopped && bus.now_us() < deadline) {
    uint8_t answered = 0;
    sdo.transfer_all_joints(SdoKind::kUploadRequest, cia402::kStatusword, 0, 0, 0, &answered);
    const uint64_t now = bus.now_us();
    for (int j = 0; j < kJointNodes; ++j) {
      const auto bit = static_cast<uint8_t>(1u << j);
      if ((answered & bit) == 0 || (r.standstill & bit) != 0) continue;
      if (!stands_still(static_cast<uint16_t>(sdo.joint_value(j)))) continue;
      r.standstill = static_cast<uint8_t>(r.standstill | bit);
      r.standstill_us = static_cast<uint32_t>(now - t0);
    }
    if (r.standstill != r.quick_stopped) master.listen(kPollUs);
  }
  sdo.transfer_all_joints(SdoKind::kDownloadRequest, cia402::kControlword, 0,
                          cia402::kCwDisableVoltage, 2, &r.disabled);
  release_drives(master);
  master.nmt().send(NmtCommand::kStop);
  master.heartbeat_producer().stop();
  master.set_stopping(false);
  master.restore_fault(cause);
  return r;
}

}  // namespace curio::app
