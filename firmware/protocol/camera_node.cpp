#include "firmware/protocol/camera_node.hpp"

namespace curio::protocol {

bool CameraNode::sdo(SdoMessage* m, NodeIo* io, EpisodeStart* start) {
  *start = EpisodeStart::kNone;
  const bool write = sdo_is_write(*m);
  bool handled = false;
  const uint8_t error_register = consumer.missed() ? od::kErrorRegisterCommunication : 0;
  const bool ok = sdo_communication(m, error_register, io, &handled);
  if (handled) return ok;
  switch (m->index) {
    case od::kEpisodeControl:
      if (m->subindex == od::kEpisodeIndexedSub) {
        if (write) return sdo_abort(m, kSdoAbortReadOnly);
        return sdo_value(m, episode_indexed ? 1u : 0u, 1);
      }
      if (m->subindex == 0) return sdo_read_only(m, od::kEpisodeIndexedSub, 1);
      if (m->subindex != od::kEpisodeStartSub) return sdo_abort(m, kSdoAbortNoSubindex);
      if (!write) return sdo_value(m, episode, 4);
      *start = episode_started && m->value == episode ? EpisodeStart::kReplay : EpisodeStart::kNew;
      episode = m->value;
      episode_started = true;
      steps = 0;
      return true;
    case od::kCaptureContent: {
      if (m->subindex != 0) return sdo_abort(m, kSdoAbortNoSubindex);
      if (!write) return sdo_value(m, capture_content, 1);
      constexpr uint32_t kAll = od::kCaptureImage | od::kCaptureGroundTruth;
      const bool supported =
          image_sensor ? (m->value & ~kAll) == 0 : m->value == od::kCaptureGroundTruth;
      if (!supported) return sdo_abort(m, kSdoAbortValueRange);
      capture_content = static_cast<uint8_t>(m->value);
      return true;
    }
    case od::kSimulatorPhysics:
      if (m->subindex != 0) return sdo_abort(m, kSdoAbortNoSubindex);
      if (write) return sdo_abort(m, kSdoAbortReadOnly);
      return sdo_value(m, physics, 1);
    case od::kWorldIdentity: {
      if (!has_world) break;
      if (m->subindex > kWorldIdentityWords) return sdo_abort(m, kSdoAbortNoSubindex);
      if (write) return sdo_abort(m, kSdoAbortReadOnly);
      if (m->subindex == 0) return sdo_value(m, kWorldIdentityWords, 1);
      WorldIdentity w = world;
      w.physics = physics;
      return sdo_value(m, world_identity_word(w, m->subindex), 4);
    }
    default:
      break;
  }
  return sdo_abort(m, kSdoAbortNoObject);
}

bool CameraNode::on_capture(const CameraCapture& c, NodeIo* io) const {
  if (nmt != NmtState::kOperational) return false;
  const bool current = episode_started && c.episode == episode;
  io->count(current ? NodeIo::Event::kCaptureTaken : NodeIo::Event::kCaptureStale);
  return current;
}

size_t CameraNode::ground_truth(bool ball_grasped, double ball_x, double ball_y,
                                double distractor_x, double distractor_y,
                                CanFrame out[kGroundTruthClassicFrames]) const {
  return encode_ground_truth({episode, ball_grasped, ball_x, ball_y, distractor_x, distractor_y},
                             profile, out);
}

NodeIdentity CameraNode::camera_identity() {
  NodeIdentity i;
  i.device_type = od::kDeviceTypeCamera;
  i.vendor_id = od::kVendorId;
  i.product_code = od::kProductCodeCamera;
  i.revision = od::kRevisionNumber;
  i.serial = od::serial_number(kCameraNode);
  return i;
}

void CameraNode::reset(NmtReset r) {
  if (r == NmtReset::kNone) return;
  if (r == NmtReset::kApplication) capture_content = kDefaultCaptureContent;
  episode_started = false;
  steps = 0;
}

}  // namespace curio::protocol
