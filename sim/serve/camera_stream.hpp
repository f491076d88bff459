// curio-sim serve --camera-stream: the simulated scene as a camera on the controller's computer
// would see it. A Unix stream socket on which every connected reader gets raw RGB24 frames
// (width × height × 3 bytes, row 0 at the top, no header) at a fixed frame rate, each the
// scene as it is at that wall-clock instant (sim/render.hpp at width × height, each value
// protocol::camera_pixel as the CAN camera's). What ffmpeg reads with
//   ffmpeg -f rawvideo -pix_fmt rgb24 -video_size WxH -framerate F -i unix:PATH ...
// Writes never block the serve: a frame a reader has no room for is dropped whole (counted),
// as a camera drops frames nobody takes.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "sim/world.hpp"

namespace curio::sim::serve {

struct CameraStreamOptions {
  std::string socket_path;
  int width = 64;
  int height = 64;
  double fps = 50.0;
};

struct CameraStreamCounters {
  uint64_t frames_rendered = 0;
  uint64_t frames_sent = 0;     // whole frames written to a reader
  uint64_t frames_dropped = 0;  // a reader still had a frame pending
  uint64_t readers = 0;         // connections accepted
};

class CameraStream {
 public:
  CameraStream() = default;
  ~CameraStream();
  CameraStream(const CameraStream&) = delete;
  CameraStream& operator=(const CameraStream&) = delete;

  // Listens on options.socket_path (a stale socket file there is replaced). "" or why not.
  std::string open(const CameraStreamOptions& options);

  // Accepts readers, finishes pending writes and, when a frame is due (now_us on the
  // steady clock), renders `scene` and sends it. Returns the microseconds until the next frame.
  uint64_t tick(uint64_t now_us, const SceneState& scene);

  const CameraStreamCounters& counters() const { return counters_; }

 private:
  struct Reader {
    int fd = -1;
    size_t pending = 0;  // bytes of frame_ still to write (0: none)
    std::vector<uint8_t> frame;
  };
  void flush(Reader& r);

  CameraStreamOptions options_;
  int listen_fd_ = -1;
  uint64_t period_us_ = 20'000;
  uint64_t next_us_ = 0;
  std::vector<float> image_;
  std::vector<uint8_t> bytes_;
  std::vector<Reader> readers_;
  CameraStreamCounters counters_;
};

}  // namespace curio::sim::serve
