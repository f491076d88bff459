#include "firmware/protocol/arm_node_set.hpp"

#include "firmware/protocol/arm_objects.hpp"

namespace curio::protocol {

void ArmNodeSet::power_on(int32_t joint_limit_counts, NodeIo* io) {
  for (int j = 0; j < kJointNodes; ++j) {
    joints[j] = JointNode{};
    joints[j].id = static_cast<uint8_t>(kFirstJointNode + j);
    joints[j].limit_counts = joint_limit_counts;
    joints[j].identity = JointNode::joint_identity(joints[j].id);
  }
  camera = CameraNode{};
  camera.id = kCameraNode;
  camera.identity = CameraNode::camera_identity();
  for (JointNode& j : joints) j.set_nmt(NmtState::kPreOperational, io);
  camera.set_nmt(NmtState::kPreOperational, io);
}

CanopenNode* ArmNodeSet::node(uint8_t id) {
  if (is_joint_node(id)) return &joints[id - kFirstJointNode];
  if (id == kCameraNode) return &camera;
  return nullptr;
}

void ArmNodeSet::heartbeats_due(uint64_t now, NodeIo* io) {
  for (JointNode& j : joints) {
    j.consumer_due(now, io);
    j.heartbeat_due(now, io);
  }
  const uint8_t camera_errors = camera.consumer.missed() ? od::kErrorRegisterCommunication : 0;
  camera.consumer_due(now, camera_errors, io);
  camera.heartbeat_due(now, io);
}

uint64_t ArmNodeSet::next_heartbeat_due_us() const {
  auto earliest = [](const CanopenNode& n) {
    const uint64_t a = n.next_heartbeat_due_us();
    // The miss is reported just after the deadline.
    const uint64_t d = n.consumer.deadline_us();
    const uint64_t b = d == UINT64_MAX ? d : d + 1;
    return a < b ? a : b;
  };
  uint64_t next = earliest(camera);
  for (const JointNode& j : joints) {
    const uint64_t due = earliest(j);
    if (due < next) next = due;
  }
  return next;
}

void ArmNodeSet::on_heartbeat(const Heartbeat& hb, NodeIo* io) {
  for (JointNode& j : joints) j.on_heartbeat(hb, io);
  camera.on_heartbeat(hb, io);
}

bool ArmNodeSet::any_ramping() const {
  for (const JointNode& j : joints)
    if (j.ramping()) return true;
  return false;
}

void ArmNodeSet::ramp_period(const double actual_rad[kJointNodes], double angle_rad[kJointNodes],
                             bool stood_still[kJointNodes]) {
  for (int j = 0; j < kJointNodes; ++j) {
    stood_still[j] = false;
    JointNode& n = joints[j];
    if (n.ramping()) {
      angle_rad[j] = n.ramp_period(&stood_still[j]);
    } else if (n.follows_target()) {  // no SYNC, no fresh target: it holds its demand
      angle_rad[j] = counts_to_angle(n.drive.motion.demand_counts);
    } else {
      angle_rad[j] = actual_rad[j];
    }
  }
}

void ArmNodeSet::after_step(const int32_t actual_counts[kJointNodes], NodeIo* io) {
  for (int j = 0; j < kJointNodes; ++j) joints[j].after_step(actual_counts[j], io);
}

NmtReset ArmNodeSet::on_nmt(const NmtMessage& m, NodeIo* io) {
  auto joint = [&](JointNode* j) {
    if (j->on_nmt(m.command, io) == NmtReset::kApplication) j->reset_application();
  };
  auto reset_camera = [&]() {
    const NmtReset r = camera.on_nmt(m.command, io);
    camera.reset(r);
    return r;
  };
  if (m.node == 0) {
    for (JointNode& j : joints) joint(&j);
    return reset_camera();
  }
  if (is_joint_node(m.node)) joint(&joints[m.node - kFirstJointNode]);
  if (m.node == kCameraNode) return reset_camera();
  return NmtReset::kNone;
}

void ArmNodeSet::send_feedback(const int32_t actual_counts[kJointNodes], NodeIo* io) const {
  for (int j = 0; j < kJointNodes; ++j) {
    if (joints[j].nmt == NmtState::kOperational) io->send(joints[j].feedback(actual_counts[j]));
  }
}

bool ArmNodeSet::on_sdo(const SdoMessage& request, const int32_t actual_counts[kJointNodes],
                        NodeIo* io, CameraNode::EpisodeStart* start, SdoMessage* answer) {
  *start = CameraNode::EpisodeStart::kNone;
  if (request.kind != SdoKind::kDownloadRequest && request.kind != SdoKind::kUploadRequest)
    return false;  // client aborts need no answer
  const CanopenNode* n = node(request.node);
  if (n == nullptr || !n->serves_sdo()) {
    io->count(NodeIo::Event::kSdoIgnored);
    return false;
  }
  io->count(NodeIo::Event::kSdoRequest);
  SdoMessage m = request;
  const int j = request.node - kFirstJointNode;
  const bool ok =
      n == &camera ? camera.sdo(&m, io, start) : joints[j].sdo(&m, actual_counts[j], io);
  if (!ok) io->count(NodeIo::Event::kSdoAbort);
  if (*start != CameraNode::EpisodeStart::kNone) {
    for (JointNode& jn : joints) jn.hold_at(0);  // the world puts the arm at its start pose
  }
  *answer = sdo_answer(request, m, ok);
  return true;
}

}  // namespace curio::protocol
