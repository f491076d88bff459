// Every end of a run is a controlled stop, and the drives are configured and identified at
// start-up (firmware/app/controlled_stop.hpp, drive_config.hpp, node_identity.hpp). The
// simulated arm (curio-sim serve's node set) runs on the loopback bus; the test records every
// frame the controller sends and every frame the arm sends, and checks on the wire:
//   * a run that ends (done, a fault it cannot ride through, a stop request) sends quick stop
//     (0x6040 = 0x0002) to all 7 joints before run_over_bus returns, then waits for every
//     joint's standstill (its statusword answers) and disables them (0x6040 = 0x0000);
//   * NMT commands go to each node by id, never to 0x00;
//   * the controller's heartbeat (0x77F) is on the bus while it runs;
//   * a drive that refuses a configuration write, or reads back another value, or is not a
//     CiA 402 device, stops the start, naming node, object and value.
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <vector>

#include "firmware/app/controlled_stop.hpp"
#include "firmware/app/node_identity.hpp"
#include "firmware/protocol/arm_messages.hpp"
#include "firmware/protocol/cia402.hpp"
#include "tests/app/app_test_util.hpp"

namespace curio::app::test {
namespace {

using hal::CanFrame;
using namespace protocol;

constexpr int kBootstrap = 10;
constexpr int kEpisodes = 10;

// An SDO request frame's object and value (expedited).
bool is_sdo_request(const CanFrame& f, uint8_t* node, uint16_t* index, uint32_t* value) {
  if (f.extended() || f.id < kCobSdoRequest + 1 || f.id > kCobSdoRequest + 0x7F) return false;
  *node = static_cast<uint8_t>(f.id - kCobSdoRequest);
  *index = static_cast<uint16_t>(f.data[1] | (f.data[2] << 8));
  *value = static_cast<uint32_t>(f.data[4] | (f.data[5] << 8) | (f.data[6] << 16) |
                                 (static_cast<uint32_t>(f.data[7]) << 24));
  return true;
}

struct Wire {
  std::mutex mutex;
  std::vector<CanFrame> sent;      // by the controller, in order
  std::vector<CanFrame> answered;  // by the arm, in order
  void add(std::vector<CanFrame>* v, const CanFrame& f) {
    std::lock_guard<std::mutex> lock(mutex);
    v->push_back(f);
  }
};

struct Rig {
  std::shared_ptr<hal::LoopbackBus> wire = hal::LoopbackBus::create();
  std::unique_ptr<hal::LoopbackEndpoint> arm_end = wire->open();
  std::unique_ptr<hal::LoopbackEndpoint> controller_end = wire->open();
  FaultyBus arm{arm_end.get()};
  FaultyBus controller{controller_end.get()};
  Wire log;
  // Extra rule on the arm's answers (after logging): rewrite or drop.
  FaultyBus::Rule arm_rule;

  Rig() {
    controller.set_tx_rule([this](CanFrame& f, std::vector<CanFrame>&) {
      log.add(&log.sent, f);
      return true;
    });
    arm.set_tx_rule([this](CanFrame& f, std::vector<CanFrame>& extra) {
      const bool keep = !arm_rule || arm_rule(f, extra);
      if (keep) log.add(&log.answered, f);
      return keep;
    });
  }

  host::BusRunResult run(ControllerConfig config, const volatile int* stop = nullptr) {
    const lab::RunSpec spec = mge_efr_spec(sim::Physics::kKinematic, 21, kEpisodes, kBootstrap);
    ArmThread thread(&arm, serve_options(spec));
    host::BusRunOptions o;
    o.spec = spec;
    o.controller = config;
    o.stop_signal = stop;
    host::BusRunResult r = host::run_over_bus(&controller, o);
    thread.stop();
    return r;
  }
};

// Index in `sent` of the first quick stop to `node`, or -1.
int first_sdo(const std::vector<CanFrame>& sent, uint8_t node, uint16_t index, uint32_t value,
              size_t from = 0) {
  for (size_t i = from; i < sent.size(); ++i) {
    uint8_t n = 0;
    uint16_t x = 0;
    uint32_t v = 0;
    if (is_sdo_request(sent[i], &n, &x, &v) && sent[i].data[0] == 0x2B && n == node && x == index &&
        (v & 0xFFFF) == value)
      return static_cast<int>(i);
  }
  return -1;
}

// The controlled stop is on the wire: every joint got quick stop, then disable; the last
// statusword each joint reported says it stands still (switch on disabled after the ramp).
void expect_controlled_stop_on_the_wire(Rig& rig, const host::BusRunResult& r) {
  EXPECT_TRUE(r.stopped);
  EXPECT_TRUE(r.stop.complete()) << "quick stopped " << int(r.stop.quick_stopped) << " standstill "
                                 << int(r.stop.standstill) << " disabled " << int(r.stop.disabled)
                                 << " " << r.stop.skipped;
  for (int j = 0; j < kJointNodes; ++j) {
    const auto node = static_cast<uint8_t>(kFirstJointNode + j);
    const int quick = first_sdo(rig.log.sent, node, cia402::kControlword, cia402::kCwQuickStop);
    ASSERT_GE(quick, 0) << "no quick stop to joint " << int(node);
    const int disable = first_sdo(rig.log.sent, node, cia402::kControlword,
                                  cia402::kCwDisableVoltage, static_cast<size_t>(quick));
    EXPECT_GT(disable, quick) << "joint " << int(node) << " was not disabled after the quick stop";
    // The arm's last statusword upload answer from this joint.
    uint16_t last_sw = 0xFFFF;
    for (const CanFrame& f : rig.log.answered)
      if (!f.extended() && f.id == kCobSdoResponse + node && f.data[0] == 0x4B &&
          f.data[1] == 0x41 && f.data[2] == 0x60)
        last_sw = static_cast<uint16_t>(f.data[4] | (f.data[5] << 8));
    EXPECT_EQ(cia402::decode_state(last_sw), cia402::DriveState::kSwitchOnDisabled)
        << "joint " << int(node) << " statusword 0x" << std::hex << last_sw;
  }
}

TEST(ControlledStop, ACompletedRunEndsInAControlledStop) {
  Rig rig;
  const host::BusRunResult r = rig.run(fast_fault_config());
  ASSERT_TRUE(r.run.error.empty()) << r.run.error;
  EXPECT_EQ(r.run.final_ball.size(), static_cast<size_t>(kBootstrap + kEpisodes));
  expect_controlled_stop_on_the_wire(rig, r);
}

TEST(ControlledStop, NmtCommandsGoToEachNodeByIdAndTheHeartbeatIsProduced) {
  Rig rig;
  ControllerConfig c = fast_fault_config();
  c.drives.master_heartbeat_ms = 10;  // several within this short run
  c.drives.consumer_time_ms = 400;
  const host::BusRunResult r = rig.run(c);
  ASSERT_TRUE(r.run.error.empty()) << r.run.error;
  int nmt = 0, heartbeats = 0;
  for (const CanFrame& f : rig.log.sent) {
    if (!f.extended() && f.id == kCobNmt) {
      ++nmt;
      EXPECT_NE(f.data[1], 0) << "an NMT command to every node on the bus";
    }
    if (!f.extended() && f.id == kCobHeartbeat + DriveSafetyConfig{}.master_node) ++heartbeats;
  }
  EXPECT_GE(nmt, 8 * 4) << "reset, pre-operational, start, stop to each of 8 nodes";
  EXPECT_GE(heartbeats, 5);
  EXPECT_EQ(r.counters.heartbeats_sent, static_cast<uint64_t>(heartbeats));
}

TEST(ControlledStop, EveryNodesIdentityIsReadAndKept) {
  Rig rig;
  const host::BusRunResult r = rig.run(fast_fault_config());
  ASSERT_TRUE(r.run.error.empty()) << r.run.error;
  ASSERT_TRUE(r.identities_read);
  for (int i = 0; i < kArmNodes; ++i) {
    EXPECT_TRUE(r.nodes[i].read);
    EXPECT_TRUE(expected_device_type(i, r.nodes[i].device_type)) << i;
    EXPECT_NE(r.nodes[i].product_code, 0u) << i;
  }
  EXPECT_NE(r.nodes[0].serial, r.nodes[1].serial) << "each node its own serial number";
}

// A stop request (SIGTERM's handler sets the flag) during an episode: the run ends at once,
// nothing of the interrupted episode is archived, and the arm is stopped.
TEST(ControlledStop, AStopRequestEndsTheRunWithAControlledStop) {
  Rig rig;
  static volatile int stop = 0;
  stop = 0;
  int tpdo = 0;
  rig.arm_rule = [&](CanFrame& f, std::vector<CanFrame>&) {
    if (!f.extended() && f.id == kCobTpdo1 + 3 && ++tpdo == 420) stop = 15;  // episode 8
    return true;
  };
  const host::BusRunResult r = rig.run(fast_fault_config(), &stop);
  EXPECT_FALSE(r.run.error.empty());
  EXPECT_EQ(r.stop_signal, 15);
  EXPECT_EQ(r.counters.faults[static_cast<size_t>(Fault::kStopRequested)], 1u);
  EXPECT_EQ(r.counters.replays, 0u) << "a stop request is not replayed";
  EXPECT_LT(r.run.final_ball.size(), static_cast<size_t>(kBootstrap + kEpisodes));
  expect_controlled_stop_on_the_wire(rig, r);
}

// Faults the run cannot ride through (one attempt allowed) end in the same controlled stop.
TEST(ControlledStop, ADriveFaultThatEndsTheRunEndsInAControlledStop) {
  Rig rig;
  int tpdo = 0;
  rig.arm_rule = [&](CanFrame& f, std::vector<CanFrame>&) {
    if (!f.extended() && f.id == kCobTpdo1 + 5 && ++tpdo == 150) f.data[0] = 0x08;  // fault
    return true;
  };
  ControllerConfig c = fast_fault_config();
  c.max_attempts = 1;
  const host::BusRunResult r = rig.run(c);
  EXPECT_FALSE(r.run.error.empty());
  EXPECT_EQ(r.counters.faults[static_cast<size_t>(Fault::kDriveFault)], 1u);
  expect_controlled_stop_on_the_wire(rig, r);
}

TEST(ControlledStop, AnEmergencyThatEndsTheRunEndsInAControlledStop) {
  Rig rig;
  int tpdo = 0;
  rig.arm_rule = [&](CanFrame& f, std::vector<CanFrame>& extra) {
    if (!f.extended() && f.id == kCobTpdo1 + 2 && ++tpdo == 150)
      extra.push_back(encode_emcy({2, 0x8611, 0x01, {}}));  // following error
    return true;
  };
  ControllerConfig c = fast_fault_config();
  c.max_attempts = 1;
  const host::BusRunResult r = rig.run(c);
  EXPECT_FALSE(r.run.error.empty());
  EXPECT_EQ(r.counters.faults[static_cast<size_t>(Fault::kFollowingError)], 1u)
      << "EMCY 0x8611 is the drive's following error";
  EXPECT_EQ(r.counters.last_emcy_code, 0x8611);
  EXPECT_EQ(r.counters.last_emcy_node, 2);
  expect_controlled_stop_on_the_wire(rig, r);
}

TEST(ControlledStop, ALostNodeThatEndsTheRunEndsInAControlledStopOfTheOthers) {
  Rig rig;
  std::atomic<bool> silent{false};
  int tpdo = 0;
  rig.arm_rule = [&](CanFrame& f, std::vector<CanFrame>&) {
    if (!f.extended() && f.id == kCobTpdo1 + 6 && ++tpdo == 150) silent = true;
    return !(silent && !f.extended() && (f.id & 0x7F) == 6 && f.id >= 0x080 && f.id < 0x780);
  };
  ControllerConfig c = fast_fault_config();
  c.max_attempts = 1;
  c.recovery_timeout_us = 300'000;
  c.stop_timeout_us = 500'000;
  const host::BusRunResult r = rig.run(c);
  EXPECT_FALSE(r.run.error.empty());
  EXPECT_TRUE(r.stop.sent);
  EXPECT_FALSE(r.stop.complete()) << "joint 6 cannot confirm";
  EXPECT_EQ(r.stop.quick_stopped, kAllJoints & ~(1u << 5)) << "every joint but 6 took it";
  EXPECT_EQ(r.stop.standstill, r.stop.quick_stopped);
}

// A joint rebooted mid-episode (its boot-up: a rogue NMT reset reaches only the arm) with one
// attempt allowed: the run ends, and the stop reaches every joint (the rebooted one too: it
// answers SDO in pre-operational).
TEST(ControlledStop, ARebootedNodeThatEndsTheRunEndsInAControlledStop) {
  Rig rig;
  std::unique_ptr<hal::LoopbackEndpoint> rogue = rig.wire->open();
  // The controller does not see the rogue's NMT (it would be another master's).
  rig.controller.set_rx_rule(
      [](CanFrame& f, std::vector<CanFrame>&) { return !(!f.extended() && f.id == kCobNmt); });
  int tpdo = 0;
  rig.arm_rule = [&](CanFrame& f, std::vector<CanFrame>&) {
    if (!f.extended() && f.id == kCobTpdo1 + 2 && ++tpdo == 150)
      rogue->send(encode_nmt({NmtCommand::kResetNode, 2}), rogue->now_us() + 100'000);
    return true;
  };
  ControllerConfig c = fast_fault_config();
  c.max_attempts = 1;
  const host::BusRunResult r = rig.run(c);
  EXPECT_FALSE(r.run.error.empty());
  EXPECT_EQ(r.counters.node_reboots, 1u);
  EXPECT_TRUE(r.stop.sent);
  EXPECT_EQ(r.stop.quick_stopped, kAllJoints);
  EXPECT_EQ(r.stop.standstill, kAllJoints);
}

// Bus-off for good: nothing can be sent, so the stop says so (the drives stop on the missed
// heartbeat), and the run ends naming the hold time.
TEST(ControlledStop, OnABusThatIsOffTheStopSaysTheDrivesStopByThemselves) {
  Rig rig;
  int tpdo = 0;
  rig.arm_rule = [&](CanFrame& f, std::vector<CanFrame>&) {
    if (!f.extended() && f.id == kCobTpdo1 + 1 && ++tpdo == 150)
      rig.controller_end->force_state(hal::BusState::kBusOff);
    return true;
  };
  ControllerConfig c = fast_fault_config();
  c.recovery_timeout_us = 300'000;
  c.max_attempts = 1;
  const host::BusRunResult r = rig.run(c);
  EXPECT_FALSE(r.run.error.empty());
  EXPECT_TRUE(r.stopped);
  EXPECT_FALSE(r.stop.sent);
  EXPECT_NE(std::string(r.stop.skipped).find("missing the controller's heartbeat"),
            std::string::npos)
      << r.stop.skipped;
}

// A drive that refuses a configuration write: the start is refused, naming node, object and
// value; nothing moved.
TEST(ControlledStop, ADriveThatRefusesItsConfigurationIsNamed) {
  Rig rig;
  rig.arm_rule = [&](CanFrame& f, std::vector<CanFrame>&) {
    // Node 4 answers the write of 0x6085 (quick-stop deceleration) with an abort.
    if (!f.extended() && f.id == kCobSdoResponse + 4 && f.data[0] == 0x60 && f.data[1] == 0x85 &&
        f.data[2] == 0x60) {
      f.data[0] = 0x80;
      const uint32_t abort = 0x06090030;  // value range exceeded
      for (int b = 0; b < 4; ++b) f.data[4 + b] = static_cast<uint8_t>(abort >> (8 * b));
    }
    return true;
  };
  const host::BusRunResult r = rig.run(fast_fault_config());
  ASSERT_FALSE(r.run.error.empty());
  EXPECT_NE(r.run.error.find("drive node 4 refused its configuration: object 0x6085.0"),
            std::string::npos)
      << r.run.error;
  EXPECT_NE(r.run.error.find("SDO abort 0x06090030"), std::string::npos) << r.run.error;
  EXPECT_TRUE(r.run.final_ball.empty());
  EXPECT_EQ(first_sdo(rig.log.sent, 4, cia402::kControlword, cia402::kCwEnableOperation), -1)
      << "no joint was enabled";
}

TEST(ControlledStop, ADriveThatDoesNotKeepAValueIsNamed) {
  Rig rig;
  rig.arm_rule = [&](CanFrame& f, std::vector<CanFrame>&) {
    // Node 3 reads back a narrower software limit (0x607D.2) than was written.
    if (!f.extended() && f.id == kCobSdoResponse + 3 && f.data[0] == 0x43 && f.data[1] == 0x7D &&
        f.data[2] == 0x60 && f.data[3] == 2)
      f.data[4] = static_cast<uint8_t>(f.data[4] ^ 0x01);
    return true;
  };
  const host::BusRunResult r = rig.run(fast_fault_config());
  ASSERT_FALSE(r.run.error.empty());
  EXPECT_NE(r.run.error.find("drive node 3 refused its configuration: object 0x607D.2"),
            std::string::npos)
      << r.run.error;
  EXPECT_NE(r.run.error.find("reads back"), std::string::npos) << r.run.error;
}

TEST(ControlledStop, ANodeOfAnotherDeviceTypeIsRefused) {
  Rig rig;
  rig.arm_rule = [&](CanFrame& f, std::vector<CanFrame>&) {
    // Node 2 says it is a CiA 401 I/O module.
    if (!f.extended() && f.id == kCobSdoResponse + 2 && f.data[0] == 0x43 && f.data[1] == 0x00 &&
        f.data[2] == 0x10) {
      f.data[4] = 0x91;  // 401 = 0x0191
      f.data[5] = 0x01;
    }
    return true;
  };
  const host::BusRunResult r = rig.run(fast_fault_config());
  ASSERT_FALSE(r.run.error.empty());
  EXPECT_NE(r.run.error.find("node 2's device type (0x1000) is 0x"), std::string::npos)
      << r.run.error;
  EXPECT_NE(r.run.error.find("not a CiA 402 drive"), std::string::npos) << r.run.error;
}

}  // namespace
}  // namespace curio::app::test
