// The camera node (0x20) as a CANopen node: the NMT/heartbeat node (with the CiA 301 objects
// of canopen_node.hpp: identity, error register, heartbeat consumer) with the camera's
// manufacturer objects (arm_objects.hpp: episode start 0x2000.1, episode-indexed scenes
// 0x2000.2, capture content 0x2001, simulator physics 0x2002, world identity 0x2003) and the capture
// request's check. What it captures and how the world starts or replays an episode is the owner's
// (the simulated arm, the fake arm).
#pragma once
#include <cstddef>
#include <cstdint>

#include "firmware/protocol/arm_messages.hpp"
#include "firmware/protocol/arm_objects.hpp"
#include "firmware/protocol/canopen_node.hpp"
#include "firmware/protocol/world_identity.hpp"

namespace curio::protocol {

struct CameraNode : CanopenNode {
  static constexpr uint8_t kDefaultCaptureContent = od::kCaptureImage | od::kCaptureGroundTruth;

  // What the owner presents (0x2002), and whether it can take images: without an image
  // sensor only the ground truth can be captured (0x2001 = 0x02).
  uint8_t physics = od::kPhysicsKinematic;
  bool image_sensor = true;
  // 0x2000.2: the owner's scenes are a function of (run seed, episode number); 0x2003: the
  // owner's world (world_identity.hpp; absent when has_world is false: a real arm). Its physics
  // is `physics` above.
  bool episode_indexed = false;
  bool has_world = false;
  WorldIdentity world;

  // The bus's profile (the owner sets it from hal::CanBus::carries_fd()): how the ground truth
  // and the image travel.
  CanProfile profile = CanProfile::kFd;

  uint8_t capture_content = kDefaultCaptureContent;
  bool episode_started = false;
  uint32_t episode = 0;
  int steps = 0;  // world steps of the episode so far (the owner's count)

  enum class EpisodeStart : uint8_t { kNone, kNew, kReplay };
  // The camera's objects. An episode start sets *start: the next episode, or the previous one
  // again (the same number) for the owner's world to replay. False: abort code in m->value.
  bool sdo(SdoMessage* m, NodeIo* io, EpisodeStart* start);

  // A capture request: true to take it (counted kCaptureTaken); ignored outside operational,
  // stale (counted) for another episode than the current one.
  bool on_capture(const CameraCapture& c, NodeIo* io) const;

  // The ground-truth message of the current episode for the owner's scene, in `profile`'s
  // frames: fills out[0..n) and returns n (1 FD frame or 5 classic ones, sent in order).
  size_t ground_truth(bool ball_grasped, double ball_x, double ball_y, double distractor_x,
                      double distractor_y, CanFrame out[kGroundTruthClassicFrames]) const;

  // The camera's identity (0x1000: no device profile, 0x1018).
  static NodeIdentity camera_identity();

  // After an NMT reset: no episode; a node reset also restores the capture content.
  void reset(NmtReset r);
};

}  // namespace curio::protocol
