// A camera on the controller's own computer (ControllerConfig::camera_on_bus false): where the
// capture takes an episode's frame when no camera node is on the bus. Firmware-clean: the
// source owns its clock and its buffer (the host's is host_tools/controller/camera_command.hpp,
// a process whose standard output is raw RGB24 frames; a board's would be its DCMI driver).
//
//   source.request_frame(settle_us);            // the episode's last period has just ended
//   while ((s = source.poll_frame(frame)) == FrameStatus::kPending) { ...keep the bus alive... }
//
// The frame taken is the first one that *arrived* settle_us or more after request_frame(): a
// frame exposed while the arm still moved, or an older one kept in a buffer, is never taken.
// poll_frame never blocks: the controller keeps pumping the bus (heartbeats) while it waits.
#pragma once
#include <cstdint>

#include "firmware/protocol/arm_messages.hpp"

namespace curio::app {

enum class FrameStatus : uint8_t {
  kPending = 0,  // no fresh frame yet
  kFresh,        // `frame` holds the 64×64×3 HWC bytes of a frame that arrived after the settle time
  kFailed,       // the source stalled, ended or gave a frame of the wrong size (the source says which)
};

class FrameSource {
 public:
  // The arm holds still from now on: the next frame taken must arrive settle_us or later.
  virtual void request_frame(uint32_t settle_us) = 0;
  // kFresh writes protocol::kCameraImageBytes bytes into `frame`.
  virtual FrameStatus poll_frame(uint8_t* frame) = 0;

 protected:
  ~FrameSource() = default;
};

}  // namespace curio::app
