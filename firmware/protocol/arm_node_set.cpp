#include "firmware/protocol/arm_node_set.hpp"

namespace curio::protocol {

void ArmNodeSet::power_on(int32_t joint_limit_counts, NodeIo* io) {
  for (int j = 0; j < kJointNodes; ++j) {
    joints[j] = JointNode{};
    joints[j].id = static_cast<uint8_t>(kFirstJointNode + j);
    joints[j].limit_counts = joint_limit_counts;
  }
  camera = CameraNode{};
  camera.id = kCameraNode;
  for (JointNode& j : joints) j.set_nmt(NmtState::kPreOperational, io);
  camera.set_nmt(NmtState::kPreOperational, io);
}

CanopenNode* ArmNodeSet::node(uint8_t id) {
  if (is_joint_node(id)) return &joints[id - kFirstJointNode];
  if (id == kCameraNode) return &camera;
  return nullptr;
}

void ArmNodeSet::heartbeats_due(uint64_t now, NodeIo* io) {
  for (JointNode& j : joints) j.heartbeat_due(now, io);
  camera.heartbeat_due(now, io);
}

uint64_t ArmNodeSet::next_heartbeat_due_us() const {
  uint64_t next = camera.next_heartbeat_due_us();
  for (const JointNode& j : joints) {
    const uint64_t due = j.next_heartbeat_due_us();
    if (due < next) next = due;
  }
  return next;
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
  *answer = sdo_answer(request, m, ok);
  return true;
}

}  // namespace curio::protocol
