// Controller side of fault handling: every fault has defined behaviour. The simulated arm runs
// behind a FaultyBus (a misbehaving node: frames dropped, rewritten, reordered, injected) or
// beside a rogue endpoint on the loopback bus. Defined behaviour checked each time:
//   * the fault is detected and counted (by kind);
//   * nothing outside the joint limits is ever sent;
//   * the attempt ends, the arm is brought back and the episode replayed (or, when it cannot
//     be, the run ends with an error) — so the archive still equals curio-lab's in-process
//     archive bit for bit: no outcome from a corrupted or incomplete observation got in.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>

#include "firmware/protocol/arm_messages.hpp"
#include "firmware/protocol/arm_objects.hpp"
#include "tests/app/app_test_util.hpp"

namespace curio::app::test {
namespace {

using hal::CanFrame;
using namespace protocol;

constexpr int kBootstrap = 20;
constexpr int kEpisodes = 20;  // 40 episodes per test

bool is_tpdo(const CanFrame& f, uint8_t node) {
  return !f.extended() && f.id == kCobTpdo1 + node;
}
bool from_node(const CanFrame& f, uint8_t node) {
  return !f.extended() && (f.id & 0x7F) == node && f.id >= 0x080 && f.id < 0x780;
}
int isotp_type(const CanFrame& f) {
  return f.extended() && f.id == kCameraImageId ? f.data[0] >> 4 : -1;
}

struct Outcome {
  host::BusRunResult bus;
  ArchiveCopy archive;
  InProcess local;
  sim::serve::ServeCounters arm;
};

// One wire: the arm behind `faulty`, the controller, and a spare (rogue) endpoint.
struct Rig {
  std::shared_ptr<hal::LoopbackBus> wire = hal::LoopbackBus::create();
  std::unique_ptr<hal::LoopbackEndpoint> arm_end = wire->open();
  std::unique_ptr<hal::LoopbackEndpoint> controller_end = wire->open();
  std::unique_ptr<hal::LoopbackEndpoint> rogue = wire->open();
  FaultyBus faulty{arm_end.get()};
  // The controller's side: rogue frames that stand for a node's own event (a reboot, a stop,
  // a bad target) reach only the arm when hide_rogue_master_frames() was called; otherwise
  // the controller sees them as another master's (a fatal fault).
  FaultyBus controller_side{controller_end.get()};

  void hide_rogue_master_frames() {
    controller_side.set_rx_rule([](CanFrame& f, std::vector<CanFrame>&) {
      uint8_t node = 0;
      const MessageKind k = classify(f, &node);
      return k != MessageKind::kNmt && k != MessageKind::kJointCommand;
    });
  }

  // twin_arm_bus: a second arm with the same ids on that bus (ArmThread's twin).
  Outcome run(const ControllerConfig& config, sim::Physics physics = sim::Physics::kKinematic,
              int episodes = kEpisodes, uint64_t seed = 21, hal::CanBus* twin_arm_bus = nullptr) {
    Outcome o;
    const lab::RunSpec spec = mge_efr_spec(physics, seed, episodes, kBootstrap);
    o.local = run_in_process(spec);
    o.bus = run_with_arm(&faulty, &controller_side, spec, config, &o.archive, &o.arm,
                         twin_arm_bus);
    std::printf(
        "faults: %s; replays %llu, capture retries %llu, foreign %llu, malformed %llu, "
        "unexpected %llu\n",
        host::fault_summary(o.bus.counters).c_str(),
        static_cast<unsigned long long>(o.bus.counters.replays),
        static_cast<unsigned long long>(o.bus.counters.capture_retries),
        static_cast<unsigned long long>(o.bus.counters.foreign_frames),
        static_cast<unsigned long long>(o.bus.counters.malformed_frames),
        static_cast<unsigned long long>(o.bus.counters.unexpected_frames));
    return o;
  }
};

uint64_t fault_count(const Outcome& o, Fault f) {
  return o.bus.counters.faults[static_cast<size_t>(f)];
}

// A run a fatal fault stopped: fewer episodes than asked, and those archived are the
// undisturbed run's.
void expect_stopped_early_with_parity(const Outcome& o) {
  const size_t done = o.bus.run.final_ball.size();
  EXPECT_LT(done, static_cast<size_t>(kBootstrap + kEpisodes));
  for (size_t e = 0; e < done; ++e) EXPECT_EQ(o.bus.run.final_ball[e], o.local.run.final_ball[e]);
}

void expect_recovered_with_parity(const Outcome& o) {
  ASSERT_TRUE(o.bus.run.error.empty()) << o.bus.run.error;
  EXPECT_GE(o.bus.counters.replays + o.bus.counters.capture_retries, 1u) << "the fault was retried";
  EXPECT_TRUE(archives_identical(o.archive, o.local.archive));
  EXPECT_EQ(o.bus.run.final_ball, o.local.run.final_ball);
}

TEST(Faults, LostFeedbackFrameEndsTheAttemptAndTheEpisodeIsReplayed) {
  Rig rig;
  int tpdo = 0;
  rig.faulty.set_tx_rule([&](CanFrame& f, std::vector<CanFrame>&) {
    return !(is_tpdo(f, 3) && ++tpdo == 130);  // episode 2, cycle 30
  });
  const Outcome o = rig.run(fast_fault_config());
  expect_recovered_with_parity(o);
  EXPECT_EQ(fault_count(o, Fault::kFeedbackTimeout), 1u);
  EXPECT_EQ(o.bus.counters.last_fault_node, 3);
  EXPECT_EQ(o.bus.counters.replays, 1u);
  EXPECT_EQ(o.arm.replays, 1u) << "the camera node rewound the episode";
}

TEST(Faults, SilentNodeIsDetectedAndTheRunResumesWhenItIsBack) {
  Rig rig;
  int tpdo = 0;
  std::chrono::steady_clock::time_point silent_until{};
  rig.faulty.set_tx_rule([&](CanFrame& f, std::vector<CanFrame>&) {
    if (!from_node(f, 5)) return true;
    const auto now = std::chrono::steady_clock::now();
    if (is_tpdo(f, 5) && ++tpdo == 200) silent_until = now + std::chrono::milliseconds(800);
    return now >= silent_until;  // node 5 says nothing (TPDO, heartbeat, SDO) for 800 ms
  });
  const Outcome o = rig.run(fast_fault_config(), sim::Physics::kOde);
  expect_recovered_with_parity(o);
  EXPECT_GE(fault_count(o, Fault::kFeedbackTimeout) + fault_count(o, Fault::kHeartbeatLost), 1u);
  EXPECT_GE(fault_count(o, Fault::kSdoTimeout), 1u) << "recovery tried while node 5 was silent";
}

TEST(Faults, HeartbeatLossAloneIsAFault) {
  Rig rig;
  int tpdo = 0;
  std::chrono::steady_clock::time_point quiet_from{}, quiet_until{};
  rig.faulty.set_tx_rule([&](CanFrame& f, std::vector<CanFrame>&) {
    // From node 6's 100th TPDO on, for 700 ms, it keeps answering SYNCs (each 1 ms late, so
    // that this outlasts the heartbeat timeout) but sends no heartbeat.
    const auto now = std::chrono::steady_clock::now();
    if (is_tpdo(f, 6) && ++tpdo == 100) {
      quiet_from = now;
      quiet_until = now + std::chrono::milliseconds(700);
    }
    const bool quiet = tpdo >= 100 && now >= quiet_from && now < quiet_until;
    if (quiet && is_tpdo(f, 6)) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return !(f.id == kCobHeartbeat + 6 && quiet);
  });
  const Outcome o = rig.run(fast_fault_config());
  expect_recovered_with_parity(o);
  EXPECT_GE(fault_count(o, Fault::kHeartbeatLost), 1u);
  EXPECT_EQ(o.bus.counters.last_fault_node, 6);
}

TEST(Faults, AControllerThatStallsDoesNotCallNodesLostWhoseHeartbeatsWaitInItsQueue) {
  // The controller stops reading the bus for longer than its heartbeat timeout once (as a
  // Cortex-M7 image does during a slow encoder inference on QEMU under load) while the arm's
  // nodes keep sending their heartbeats: they wait in its receive queue, so no node is lost.
  Rig rig;
  int tpdo = 0;
  const ControllerConfig config = fast_fault_config();
  rig.controller_side.set_rx_rule([&](CanFrame& f, std::vector<CanFrame>&) {
    if (is_tpdo(f, 3) && ++tpdo == 300)
      std::this_thread::sleep_for(std::chrono::microseconds(config.heartbeat_timeout_us + 300'000));
    return true;
  });
  const Outcome o = rig.run(config);
  ASSERT_TRUE(o.bus.run.error.empty()) << o.bus.run.error;
  ASSERT_GE(tpdo, 300) << "the stall happened";
  EXPECT_EQ(fault_count(o, Fault::kHeartbeatLost), 0u) << host::fault_summary(o.bus.counters);
  EXPECT_TRUE(archives_identical(o.archive, o.local.archive));
}

TEST(Faults, ADriveThatLostAnEarlierControllerIsBroughtBackNotCountedAgainstThisRun) {
  // A resumed controller starts while the drives stop on the killed one's missed heartbeat:
  // their EMCY 0x8130 arrives during this bring-up, before it configures their consumers.
  // Counted, no fault: the bring-up re-arms the consumers and enables the drives.
  Rig rig;
  rig.hide_rogue_master_frames();
  protocol::Emergency e;
  e.node = 4;
  e.error_code = kEmcyHeartbeatError;
  ASSERT_EQ(rig.rogue->send(encode_emcy(e), rig.rogue->now_us() + 100'000), hal::CanStatus::kOk);
  const Outcome o = rig.run(fast_fault_config());
  ASSERT_TRUE(o.bus.run.error.empty()) << o.bus.run.error;
  EXPECT_EQ(fault_count(o, Fault::kMasterHeartbeatMissed), 0u);
  EXPECT_EQ(o.bus.counters.last_emcy_code, kEmcyHeartbeatError) << "the EMCY was seen";
  EXPECT_TRUE(archives_identical(o.archive, o.local.archive));
}

// A real drive fault: a rogue frame gives joint 2 a target outside its range; the node
// refuses it, raises EMCY 0x8612 and goes to "fault". The controller resets the fault.
TEST(Faults, EmergencyAndDriveFaultAreResetAndTheEpisodeReplayed) {
  Rig rig;
  rig.hide_rogue_master_frames();
  int tpdo = 0;
  rig.faulty.set_tx_rule([&](CanFrame& f, std::vector<CanFrame>&) {
    if (is_tpdo(f, 2) && ++tpdo == 222) {
      const CanFrame bad =
          encode_joint_command({2, cia402::kCwEnableOperation, kJointLimitCounts + 5});
      rig.rogue->send(bad, rig.rogue->now_us() + 100'000);
    }
    return true;
  });
  const Outcome o = rig.run(fast_fault_config(), sim::Physics::kOde);
  expect_recovered_with_parity(o);
  EXPECT_EQ(o.arm.rejected_targets, 1u) << "the joint never applied the out-of-range target";
  EXPECT_EQ(o.arm.emcy_sent, 1u);
  EXPECT_EQ(fault_count(o, Fault::kEmergency) + fault_count(o, Fault::kDriveFault), 1u);
  EXPECT_EQ(o.bus.counters.emergencies, 1u);
  EXPECT_EQ(o.bus.counters.last_fault_node, 2);
}

TEST(Faults, StatuswordFaultWithoutEmcyIsAFault) {
  Rig rig;
  int tpdo = 0;
  rig.faulty.set_tx_rule([&](CanFrame& f, std::vector<CanFrame>&) {
    if (is_tpdo(f, 7) && ++tpdo == 140) f.data[0] = 0x08;  // statusword: fault
    return true;
  });
  const Outcome o = rig.run(fast_fault_config());
  expect_recovered_with_parity(o);
  EXPECT_EQ(fault_count(o, Fault::kDriveFault), 1u);
}

TEST(Faults, FollowingErrorIsAFault) {
  Rig rig;
  int tpdo = 0;
  rig.faulty.set_tx_rule([&](CanFrame& f, std::vector<CanFrame>&) {
    if (is_tpdo(f, 4) && ++tpdo == 77) f.data[4] ^= 0x01;  // actual position off by 65536 µrad
    return true;
  });
  const Outcome o = rig.run(fast_fault_config());
  expect_recovered_with_parity(o);
  EXPECT_EQ(fault_count(o, Fault::kFollowingError), 1u);
}

TEST(Faults, StoppedNodeIsAFaultAndIsStartedAgain) {
  Rig rig;
  rig.hide_rogue_master_frames();
  int tpdo = 0;
  rig.faulty.set_tx_rule([&](CanFrame& f, std::vector<CanFrame>&) {
    if (is_tpdo(f, 6) && ++tpdo == 180)
      rig.rogue->send(encode_nmt({NmtCommand::kStop, 6}), rig.rogue->now_us() + 100'000);
    return true;
  });
  const Outcome o = rig.run(fast_fault_config());
  expect_recovered_with_parity(o);
  EXPECT_GE(fault_count(o, Fault::kNodeState) + fault_count(o, Fault::kFeedbackTimeout), 1u);
}

TEST(Faults, RebootedNodeIsReconfigured) {
  Rig rig;
  rig.hide_rogue_master_frames();
  int tpdo = 0;
  rig.faulty.set_tx_rule([&](CanFrame& f, std::vector<CanFrame>&) {
    if (is_tpdo(f, 2) && ++tpdo == 260)
      rig.rogue->send(encode_nmt({NmtCommand::kResetNode, 2}), rig.rogue->now_us() + 100'000);
    return true;
  });
  const Outcome o = rig.run(fast_fault_config());
  expect_recovered_with_parity(o);
  EXPECT_GE(fault_count(o, Fault::kNodeState) + fault_count(o, Fault::kFeedbackTimeout), 1u);
  EXPECT_EQ(o.bus.counters.node_reboots, 1u) << "node 2's boot-up, which we did not cause";
}

// Another master's SYNC mid-run (it would step the world under our episode): fatal, no
// replay, the run stops naming it; what was archived before stays the in-process run's.
TEST(Faults, AnotherMastersFramesStopTheRunWithoutReplay) {
  Rig rig;
  int tpdo = 0;
  rig.faulty.set_tx_rule([&](CanFrame& f, std::vector<CanFrame>&) {
    if (is_tpdo(f, 5) && ++tpdo == 300)
      rig.rogue->send(encode_sync(0), rig.rogue->now_us() + 100'000);
    return true;
  });
  const Outcome o = rig.run(fast_fault_config());
  ASSERT_FALSE(o.bus.run.error.empty());
  EXPECT_NE(o.bus.run.error.find("another master is on this bus"), std::string::npos)
      << o.bus.run.error;
  EXPECT_EQ(fault_count(o, Fault::kOtherMaster), 1u);
  EXPECT_EQ(o.bus.counters.replays, 0u) << "no replay can cure a second master";
  EXPECT_GE(o.bus.counters.other_master_frames, 1u);
  expect_stopped_early_with_parity(o);
}

// A second arm (a second curio-sim serve) on the same wire: every SDO request is answered
// twice; the controller stops at the first second answer, whether it arrives while its
// request is still the pending one or just after the master moved on to the node's next
// transfer (the second arm is the slower one). It stops with the fault named, before any
// episode, and what it archived before is what an undisturbed run has. The two arms answer
// from one thread in turn (ArmThread's twin): with a thread each, the host's scheduler can
// hold one arm back for a whole bring-up, and its stale heartbeat then fails the start
// (AStaleHeartbeatOfASecondArmAtStartIsNamed).
TEST(Faults, SecondArmOnTheBusIsRefused) {
  Rig rig;
  const Outcome o = rig.run(fast_fault_config(), sim::Physics::kKinematic, kEpisodes, 21,
                            rig.rogue.get());
  ASSERT_FALSE(o.bus.run.error.empty());
  EXPECT_NE(o.bus.run.error.find("two nodes answer as node"), std::string::npos) << o.bus.run.error;
  EXPECT_EQ(fault_count(o, Fault::kDuplicateNode), 1u);
  EXPECT_GE(o.bus.counters.duplicate_answers, 1u);
  expect_stopped_early_with_parity(o);
}

// The slower of two arms, seen from the first: once the first arm's last node (the camera)
// said "operational", the rogue endpoint sends `late` (before the arm's next frame). Returns
// whether it was sent.
std::shared_ptr<bool> rogue_sends_once_the_arm_is_up(Rig& rig, CanFrame late) {
  auto sent = std::make_shared<bool>(false);
  auto up = std::make_shared<bool>(false);
  rig.faulty.set_tx_rule([&rig, late, sent, up](CanFrame& f, std::vector<CanFrame>&) {
    uint8_t node = 0;
    Heartbeat hb;
    if (*up && !*sent) {  // the rogue's frame goes out before this one, after that one
      rig.rogue->send(late, rig.rogue->now_us() + 100'000);
      *sent = true;
    }
    *up = *up || (classify(f, &node) == MessageKind::kHeartbeat && node == kCameraNode &&
                  decode_heartbeat(f, &hb) == CodecStatus::kOk &&
                  hb.state == NmtState::kOperational);
    return true;
  });
  return sent;
}

// The slower of two arms, as a loaded machine schedules it: its periodic heartbeat, sent
// before it handled our NMT start, comes just after the first arm's "operational". A single
// node never goes back from operational unless told or on an error, so the start fails naming
// two nodes with that id (or an error) instead of asking whether curio-sim serve is running.
TEST(Faults, AStaleHeartbeatOfASecondArmAtStartIsNamed) {
  Rig rig;
  const auto sent =
      rogue_sends_once_the_arm_is_up(rig, encode_heartbeat({kCameraNode, NmtState::kPreOperational}));
  const Outcome o = rig.run(fast_fault_config());
  ASSERT_TRUE(*sent);
  EXPECT_NE(o.bus.run.error.find("the arm did not come up"), std::string::npos) << o.bus.run.error;
  EXPECT_NE(o.bus.run.error.find("two nodes answer as node 32"), std::string::npos)
      << o.bus.run.error;
  EXPECT_EQ(o.bus.counters.state_regressions, 1u);
  EXPECT_EQ(o.bus.counters.last_regression_node, kCameraNode);
  EXPECT_TRUE(o.bus.run.final_ball.empty());
}

// The slower of two arms, held back until the first arm is up: its boot-up after our NMT reset
// comes after the first arm's "operational" (seen in CI on a loaded 2-core machine). A single
// node boots after operational only when it restarts, so the start fails naming two nodes with
// that id (or a restart), not asking whether curio-sim serve is running.
TEST(Faults, ALateBootUpOfASecondArmAtStartIsNamed) {
  Rig rig;
  const auto sent = rogue_sends_once_the_arm_is_up(rig, encode_heartbeat({1, NmtState::kBootUp}));
  const Outcome o = rig.run(fast_fault_config());
  ASSERT_TRUE(*sent);
  EXPECT_NE(o.bus.run.error.find("the arm did not come up"), std::string::npos) << o.bus.run.error;
  EXPECT_NE(o.bus.run.error.find("two nodes answer as node 1 "), std::string::npos)
      << o.bus.run.error;
  EXPECT_EQ(o.bus.counters.state_regressions, 1u);
  EXPECT_EQ(o.bus.counters.last_regression_node, 1);
  EXPECT_EQ(o.bus.counters.node_reboots, 1u) << "the boot-up is not one our reset caused";
  EXPECT_TRUE(o.bus.run.final_ball.empty());
}

// The slower of two arms: node 3's answer to the master's first SDO write comes a second time,
// from the rogue endpoint, only once node 3 answers the master's next transfer (so the master
// has moved on). A server answers each request once, so this is a second node with id 3.
TEST(Faults, LateSecondAnswerAfterTheMasterMovedOnIsRefused) {
  Rig rig;
  std::optional<CanFrame> first_answer;
  bool sent = false;
  rig.faulty.set_tx_rule([&](CanFrame& f, std::vector<CanFrame>&) {
    uint8_t node = 0;
    if (sent || classify(f, &node) != MessageKind::kSdoResponse || node != 3) return true;
    if (!first_answer) {
      first_answer = f;
    } else {
      rig.rogue->send(*first_answer, rig.rogue->now_us() + 100'000);  // before this answer
      sent = true;
    }
    return true;
  });
  const Outcome o = rig.run(fast_fault_config());
  ASSERT_TRUE(sent);
  ASSERT_FALSE(o.bus.run.error.empty());
  EXPECT_NE(o.bus.run.error.find("two nodes answer as node 3"), std::string::npos)
      << o.bus.run.error;
  EXPECT_EQ(fault_count(o, Fault::kDuplicateNode), 1u);
  EXPECT_EQ(o.bus.counters.duplicate_answers, 1u);
  expect_stopped_early_with_parity(o);
}

// A third process on the bus forges the scene: it answers a capture with its own ground truth
// (0x2A0) for the same episode, the ball moved by 5 cm. A camera answers each capture once, so
// two answers to one capture stop the run with the fault named (never first-wins).
CanFrame forged(const CanFrame& truth) {
  GroundTruth g;
  EXPECT_EQ(decode_ground_truth(truth, &g), CodecStatus::kOk);
  g.ball_x += 0.05;
  return encode_ground_truth(g);
}
bool is_ground_truth(const CanFrame& f) { return !f.extended() && f.id == kCobGroundTruth; }

void expect_duplicate_capture_named(const Outcome& o) {
  ASSERT_FALSE(o.bus.run.error.empty());
  EXPECT_NE(o.bus.run.error.find("two answers to one capture"), std::string::npos)
      << o.bus.run.error;
  EXPECT_EQ(fault_count(o, Fault::kDuplicateCapture), 1u);
  EXPECT_EQ(o.bus.counters.last_fault, Fault::kDuplicateCapture);
  EXPECT_LT(o.bus.run.final_ball.size(), static_cast<size_t>(kBootstrap + kEpisodes));
}

// The forger is faster: its ground truth comes before the camera's, each capture. The run
// stops at the first capture; the forged answer may have been archived before the camera's
// came (the run ends in an error, not "exact"), but nothing after it.
TEST(Faults, AForgedGroundTruthBeforeTheCamerasStopsTheRun) {
  Rig rig;
  int forged_sent = 0;
  rig.faulty.set_tx_rule([&](CanFrame& f, std::vector<CanFrame>&) {
    if (is_ground_truth(f)) {
      rig.rogue->send(forged(f), rig.rogue->now_us() + 100'000);
      ++forged_sent;
    }
    return true;
  });
  const Outcome o = rig.run(fast_fault_config());
  ASSERT_GE(forged_sent, 1);
  expect_duplicate_capture_named(o);
  EXPECT_LE(o.bus.run.final_ball.size(), 1u) << "stopped at the first capture";
}

// The forger is slower: its ground truth for episode 0 comes after the controller moved on
// (before the arm's next answer). Found there; what was archived is the camera's.
TEST(Faults, AForgedGroundTruthAfterTheCaptureStopsTheRun) {
  Rig rig;
  std::optional<CanFrame> truth;
  bool sent = false;
  rig.faulty.set_tx_rule([&](CanFrame& f, std::vector<CanFrame>&) {
    uint8_t node = 0;
    if (sent) return true;
    if (is_ground_truth(f)) {
      truth = f;
    } else if (truth && classify(f, &node) != MessageKind::kHeartbeat) {
      rig.rogue->send(forged(*truth), rig.rogue->now_us() + 100'000);
      sent = true;
    }
    return true;
  });
  const Outcome o = rig.run(fast_fault_config());
  ASSERT_TRUE(sent);
  expect_duplicate_capture_named(o);
  expect_stopped_early_with_parity(o);
}

// A second camera: once the camera's frame of episode 0 was whole, a second transfer of it
// starts (its first frame again, from the third endpoint) after the controller moved on.
TEST(Faults, ASecondCameraAnsweringACaptureStopsTheRun) {
  Rig rig;
  std::optional<CanFrame> first_frame;
  bool sent = false;
  rig.faulty.set_tx_rule([&](CanFrame& f, std::vector<CanFrame>&) {
    uint8_t node = 0;
    if (sent) return true;
    if (isotp_type(f) == 1) {
      first_frame = f;
    } else if (first_frame && isotp_type(f) < 0 &&
               classify(f, &node) != MessageKind::kHeartbeat) {
      rig.rogue->send(*first_frame, rig.rogue->now_us() + 100'000);
      sent = true;
    }
    return true;
  });
  ControllerConfig config = fast_fault_config();
  config.want_image = true;
  const Outcome o = rig.run(config);
  ASSERT_TRUE(sent);
  expect_duplicate_capture_named(o);
  expect_stopped_early_with_parity(o);
}

TEST(Faults, TransientBusOffIsWaitedOutAndTheEpisodeReplayed) {
  Rig rig;
  int tpdo = 0;
  std::chrono::steady_clock::time_point back_at{};
  bool off = false;
  rig.faulty.set_tx_rule([&](CanFrame& f, std::vector<CanFrame>&) {
    const auto now = std::chrono::steady_clock::now();
    if (is_tpdo(f, 1) && ++tpdo == 300) {
      rig.controller_end->force_state(hal::BusState::kBusOff);
      back_at = now + std::chrono::milliseconds(300);
      off = true;
    } else if (off && now >= back_at) {  // heartbeats keep this rule running meanwhile
      rig.controller_end->force_state(hal::BusState::kErrorActive);
      off = false;
    }
    return true;
  });
  const Outcome o = rig.run(fast_fault_config());
  expect_recovered_with_parity(o);
  EXPECT_GE(fault_count(o, Fault::kBusOff), 1u);
  EXPECT_EQ(rig.controller_end->stats().bus_off_events, 1u);
}

TEST(Faults, PermanentBusOffEndsTheRunCleanlyWithoutArchiving) {
  Rig rig;
  int tpdo = 0;
  rig.faulty.set_tx_rule([&](CanFrame& f, std::vector<CanFrame>&) {
    if (is_tpdo(f, 1) && ++tpdo == 520) rig.controller_end->force_state(hal::BusState::kBusOff);
    return true;
  });
  ControllerConfig config = fast_fault_config();
  config.recovery_timeout_us = 300'000;
  config.max_attempts = 2;
  const Outcome o = rig.run(config);
  EXPECT_FALSE(o.bus.run.error.empty());
  EXPECT_NE(o.bus.run.error.find("episode 10"), std::string::npos) << o.bus.run.error;
  EXPECT_EQ(o.archive.size, 10) << "episodes 0-9 archived, episode 10 (cycle 20 at bus-off) not";
  // What was archived is the in-process prefix.
  ArchiveCopy prefix = o.local.archive;
  prefix.size = 10;
  prefix.theta.resize(10 * kThetaDim);
  prefix.outcome.resize(10 * static_cast<size_t>(prefix.outcome_dim));
  EXPECT_TRUE(archives_identical(o.archive, prefix));
  EXPECT_GE(fault_count(o, Fault::kBusOff), 1u);
  EXPECT_NE(o.bus.run.error.find("did not come back within the hold time (0.3 s"), std::string::npos)
      << o.bus.run.error;
}

// Joint limits narrower than the motor primitive's range: the first target beyond them is
// never sent; the episode cannot complete, so the run stops without archiving it.
TEST(Faults, TargetsOutsideJointLimitsAreNeverSent) {
  Rig rig;
  constexpr int32_t kLimit = 2'500'000;  // ±2.5 rad: |a| ≤ 0.796
  std::atomic<int32_t> max_sent{0};
  rig.faulty.set_rx_rule([&](CanFrame& f, std::vector<CanFrame>&) {  // what reaches the arm
    JointCommand c;
    if (decode_joint_command(f, &c) == CodecStatus::kOk)
      max_sent = std::max<int32_t>(max_sent, std::abs(c.target_counts));
    return true;
  });
  ControllerConfig config = fast_fault_config();
  config.joint_limit_counts = kLimit;
  const Outcome o = rig.run(config);
  EXPECT_FALSE(o.bus.run.error.empty());
  EXPECT_LE(max_sent.load(), kLimit);
  EXPECT_GT(max_sent.load(), 0);
  EXPECT_EQ(fault_count(o, Fault::kJointLimit), config.max_attempts);
  EXPECT_EQ(o.bus.counters.last_fault, Fault::kJointLimit);
  // The arm came back after each attempt: the error says the faults recur, not that the arm
  // was lost (which is what it said before, for any failed episode).
  EXPECT_NE(o.bus.run.error.find("each of its " + std::to_string(config.max_attempts) +
                                 " attempts (--max-attempts) hit a fault"),
            std::string::npos)
      << o.bus.run.error;
  EXPECT_EQ(o.bus.run.error.find("hold time"), std::string::npos) << o.bus.run.error;
  EXPECT_LT(o.archive.size, kBootstrap + kEpisodes);
  ArchiveCopy prefix = o.local.archive;
  prefix.size = o.archive.size;
  prefix.theta.resize(static_cast<size_t>(o.archive.size) * kThetaDim);
  prefix.outcome.resize(static_cast<size_t>(o.archive.size * prefix.outcome_dim));
  EXPECT_TRUE(archives_identical(o.archive, prefix));
}

// ---- the camera frame (ISO-TP): each fault fails the capture, which is then retried.
struct ImageRule {
  int image = 0;  // FFs seen
  int cf = 0;     // CFs of the current image
};

Outcome run_with_image_fault(
    Rig& rig, std::function<bool(ImageRule&, CanFrame&, std::vector<CanFrame>&)> rule) {
  ImageRule state;
  rig.faulty.set_tx_rule([&state, rule](CanFrame& f, std::vector<CanFrame>& extra) {
    const int type = isotp_type(f);
    if (type == 1) {
      ++state.image;
      state.cf = 0;
    } else if (type == 2) {
      ++state.cf;
    }
    if (type < 0) return true;
    return rule(state, f, extra);
  });
  ControllerConfig config = fast_fault_config();
  config.want_image = true;
  return rig.run(config);
}

TEST(Faults, ImageOutOfOrderFramesAreASequenceError) {
  Rig rig;
  CanFrame held;
  const Outcome o =
      run_with_image_fault(rig, [&](ImageRule& s, CanFrame& f, std::vector<CanFrame>& extra) {
        if (s.image != 3) return true;
        if (s.cf == 5) {
          held = f;
          return false;
        }
        if (s.cf == 6) extra.push_back(held);  // CF 6 then CF 5
        return true;
      });
  expect_recovered_with_parity(o);
  EXPECT_EQ(fault_count(o, Fault::kImageError), 1u);
  EXPECT_EQ(o.bus.image.sequence_errors, 1u);
  EXPECT_EQ(o.bus.counters.capture_retries, 1u);
}

TEST(Faults, ImageTruncatedFrameIsAnError) {
  Rig rig;
  const Outcome o =
      run_with_image_fault(rig, [&](ImageRule& s, CanFrame& f, std::vector<CanFrame>&) {
        if (s.image == 4 && s.cf == 10) f.len = 32;
        return true;
      });
  expect_recovered_with_parity(o);
  EXPECT_EQ(fault_count(o, Fault::kImageError), 1u);
  EXPECT_EQ(o.bus.image.truncated, 1u);
}

TEST(Faults, ImageOversizedTransferIsRefusedWithOverflow) {
  Rig rig;
  const Outcome o =
      run_with_image_fault(rig, [&](ImageRule& s, CanFrame& f, std::vector<CanFrame>&) {
        if (s.image == 2 && s.cf == 0) {  // the first frame announces 20,000 bytes (escape form)
          f.data[0] = 0x10;
          f.data[1] = 0x00;
          f.data[2] = 0x00;
          f.data[3] = 0x00;
          f.data[4] = 0x4E;
          f.data[5] = 0x20;
        }
        return true;
      });
  expect_recovered_with_parity(o);
  EXPECT_EQ(fault_count(o, Fault::kImageError), 1u);
  EXPECT_EQ(o.bus.image.oversized, 1u);
  EXPECT_GE(o.arm.image_errors, 1u) << "the camera saw the overflow flow control";
}

TEST(Faults, ImageTransferThatStopsTimesOut) {
  Rig rig;
  const Outcome o = run_with_image_fault(rig, [&](ImageRule& s, CanFrame&, std::vector<CanFrame>&) {
    return !(s.image == 5 && s.cf >= 100);  // the rest of the frame never comes
  });
  expect_recovered_with_parity(o);
  EXPECT_EQ(fault_count(o, Fault::kCaptureTimeout), 1u);
}

TEST(Faults, GarbledGroundTruthIsNeverArchived) {
  Rig rig;
  int gt = 0;
  rig.faulty.set_tx_rule([&](CanFrame& f, std::vector<CanFrame>&) {
    if (f.id == kCobGroundTruth && !f.extended()) {
      ++gt;
      if (gt == 3) f.data[4] = 0x80;  // reserved flag bit: malformed, dropped
      if (gt == 7) {                  // decodes, but ball x is NaN
        const double nan = std::numeric_limits<double>::quiet_NaN();
        std::memcpy(f.data + 8, &nan, 8);
      }
    }
    return true;
  });
  const Outcome o = rig.run(fast_fault_config());
  expect_recovered_with_parity(o);
  EXPECT_GE(o.bus.counters.malformed_frames, 1u);
  EXPECT_EQ(fault_count(o, Fault::kCaptureTimeout), 1u);
  EXPECT_EQ(fault_count(o, Fault::kGroundTruthInvalid), 1u);
}

// A flood of foreign and malformed frames from a third node while the run goes on.
TEST(Faults, FloodOfForeignAndMalformedFramesChangesNothing) {
  Rig rig;
  std::atomic<bool> stop{false};
  std::atomic<uint64_t> flooded{0};
  std::thread flooder([&] {
    uint32_t k = 0;
    CanFrame batch[16];
    while (!stop) {
      for (CanFrame& f : batch) {
        f = CanFrame{};
        switch (k % 8) {
          case 0:
            f.id = 0x180 + 8 + k % 100;
            f.len = 6;
            break;  // TPDO of a foreign node
          case 1:
            f.id = 0x183;
            f.len = 5;
            break;  // node 3's TPDO, bad DLC
          case 2:
            f.id = 0x705;
            f.len = 2;
            break;  // heartbeat, bad DLC
          case 3:
            f.id = kCobGroundTruth;
            f.len = 8;
            break;  // ground truth, classic
          case 4:
            f.id = 0x085;
            f.len = 3;
            break;  // EMCY, bad DLC
          case 5:
            f.id = 0x18DAF1A0;
            f.flags = hal::kFlagExtended | hal::kFlagFd;
            f.len = 64;
            break;
          case 6:
            f.id = 0x7E5;
            f.len = 8;
            break;  // unknown id
          case 7:
            f.id = 0x585;
            f.len = 4;
            break;  // SDO response, bad DLC
        }
        for (size_t i = 0; i < f.len; ++i) f.data[i] = static_cast<uint8_t>(k * 13 + i);
        ++k;
      }
      if (rig.rogue->send_batch(batch, 16, rig.rogue->now_us() + 100'000, nullptr) ==
          hal::CanStatus::kOk)
        flooded += 16;
      // 16 frames per 2 ms: ≈ 8,000 frames/s, a saturated 1 Mbit/s classic CAN bus. Unpaced
      // (a 200 µs pause, ≈ 40,000 frames/s on an idle machine, more than any CAN bus carries)
      // the flood starved the arm's boot-up for 10 s once when other jobs loaded both cores.
      std::this_thread::sleep_for(std::chrono::microseconds(2000));
    }
  });
  ControllerConfig config = fast_fault_config();
  // The flood runs from before boot: on a loaded machine the boot-up heartbeats can queue
  // behind it for longer than the default 1 s; this test is about what the flood changes,
  // not about boot latency.
  config.boot_timeout_us = 10'000'000;
  const Outcome o = rig.run(config);
  stop = true;
  flooder.join();
  ASSERT_TRUE(o.bus.run.error.empty()) << o.bus.run.error;
  EXPECT_TRUE(archives_identical(o.archive, o.local.archive));
  EXPECT_GT(o.bus.counters.foreign_frames, 0u);
  EXPECT_GT(o.bus.counters.malformed_frames, 0u);
  EXPECT_GT(o.arm.foreign + o.arm.malformed, 0u);
  std::printf("flood: %llu frames sent by the flooder\n",
              static_cast<unsigned long long>(flooded.load()));
}

}  // namespace
}  // namespace curio::app::test
