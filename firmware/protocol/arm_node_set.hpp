// The arm's eight CANopen nodes together: joints 1–7 (joint_node.hpp) and the camera 0x20
// (camera_node.hpp), addressed by node id: power-on, NMT (node 0: all), heartbeats, RPDO1,
// TPDO1 after a SYNC, and the SDO server. The world they drive is the owner's (the simulated
// arm of curio-sim serve, the in-image fake arm of the Cortex-M7 controller image).
#pragma once
#include <cstdint>

#include "firmware/protocol/camera_node.hpp"
#include "firmware/protocol/joint_node.hpp"

namespace curio::protocol {

struct ArmNodeSet {
  JointNode joints[kJointNodes];
  CameraNode camera;

  // Power-on: node ids, identities and the joints' range, then every node boots into
  // pre-operational.
  void power_on(int32_t joint_limit_counts, NodeIo* io);

  // One of the eight, or nullptr.
  CanopenNode* node(uint8_t id);

  // Heartbeats the nodes produce that are due at `now`, and the heartbeat consumers' checks
  // (a joint that missed its producer reacts as its 0x6007 says).
  void heartbeats_due(uint64_t now, NodeIo* io);
  // The next heartbeat due or consumer deadline; UINT64_MAX: none.
  uint64_t next_heartbeat_due_us() const;

  // A heartbeat on the bus (any node's, the controller's included): the consumers watching it.
  void on_heartbeat(const Heartbeat& hb, NodeIo* io);

  // Whether a joint runs its quick stop or fault reaction ramp (the owner steps the world
  // with ramp_period() once per interpolation period of its own clock, SYNC or not).
  bool any_ramping() const;
  // One period of every ramping joint's ramp: angle_rad[j] for joint j (ramping joints: the
  // ramp's demand; others hold `actual_rad[j]`). stood_still[j]: joint j reached standstill.
  void ramp_period(const double actual_rad[kJointNodes], double angle_rad[kJointNodes],
                   bool stood_still[kJointNodes]);
  // After a world step: the joints' following error checks.
  void after_step(const int32_t actual_counts[kJointNodes], NodeIo* io);

  // NMT for node m.node (0: all nodes); a joint's node reset restores its drive. Returns the
  // camera's reset (kNone when the camera was not reset), for the owner's world.
  NmtReset on_nmt(const NmtMessage& m, NodeIo* io);

  void on_command(const JointCommand& c, NodeIo* io) {
    joints[c.node - kFirstJointNode].on_command(c, io);
  }

  // TPDO1 of every operational joint, with the position actual values of all seven.
  void send_feedback(const int32_t actual_counts[kJointNodes], NodeIo* io) const;

  // An SDO request. False: no answer (client aborts; counted kSdoIgnored: no such node, or a
  // stopped or booting one). Else *answer is the node's answer (counted kSdoRequest, and
  // kSdoAbort), to send once the owner's world has done a camera episode start (*start: the
  // joints' demands are then at the start pose, all zeros). The joints' position actual
  // values come from `actual_counts`.
  bool on_sdo(const SdoMessage& request, const int32_t actual_counts[kJointNodes], NodeIo* io,
              CameraNode::EpisodeStart* start, SdoMessage* answer);
};

}  // namespace curio::protocol
