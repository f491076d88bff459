// curio-controller --camera COMMAND: a camera on the controller's computer. COMMAND runs under
// /bin/sh; its standard output must be raw RGB24 frames of --camera-size (width × height × 3
// bytes each, row 0 at the top, no header), e.g. ffmpeg ... -f rawvideo -pix_fmt rgb24 -.
// A reader thread keeps only the newest whole frame and the time it arrived; the controller's
// capture (firmware/app/frame_source.hpp) takes the first frame that arrived after the arm
// settled, resampled to 64×64 as `curio-encode --resize` does (host_tools/encode/camera_png.hpp).
//
// A source that does not start (the command cannot run, exits, or sends no whole frame within
// start_timeout_ms), stalls (no frame for stall_ms), ends, or sends frames of another size (a
// PPM header that says so; raw: bytes that are not a whole number of frames) fails: poll_frame returns kFailed and failure() names why.
// The command's standard error goes to log_path.
#pragma once
#include <sys/types.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "firmware/app/frame_source.hpp"

namespace curio::app::host {

struct CameraCommandOptions {
  std::string command;
  int width = 64;
  int height = 64;
  // false: raw RGB24, no header (ffmpeg -f rawvideo -pix_fmt rgb24); a frame of another size
  // shows only when the stream ends mid-frame. true: a PPM (P6) stream (ffmpeg -f image2pipe
  // -c:v ppm), each frame's header checked against width × height.
  bool ppm = false;
  uint32_t start_timeout_ms = 10'000;  // the first whole frame within this long
  uint32_t stall_ms = 2'000;           // then no gap between frames longer than this
  std::string log_path;                // the command's stderr ("" : /dev/null)
};

// The camera's figures over a run (summary.json "camera").
struct CameraStats {
  uint64_t frames_read = 0;   // whole frames the command sent
  uint64_t frames_taken = 0;  // frames encoded (one per episode attempt that reached the capture)
  uint64_t frames_superseded = 0;  // read with a newer whole frame already behind them: skipped
  // Arrived after more than 3 × the median frame interval of silence, or in a burst (< 1/4 of
  // it): possibly held up in the pipeline, so never taken.
  uint64_t frames_distrusted = 0;
  double settle_ms = 0;        // the settle time asked for (the last request's)
  std::vector<uint64_t> sequence;  // per taken frame: its number in the stream (1 = first)
  std::vector<double> wait_ms;  // per taken frame: from the arm's last period to the frame's arrival
  std::vector<double> age_ms;   // per taken frame: from its arrival to the capture taking it
  std::vector<double> gap_ms;   // between consecutive frames read (the source's frame interval)
};

class CameraCommand final : public FrameSource {
 public:
  CameraCommand() = default;
  ~CameraCommand();
  CameraCommand(const CameraCommand&) = delete;
  CameraCommand& operator=(const CameraCommand&) = delete;

  // Starts the command and waits for its first whole frame: "" or why the camera did not start.
  std::string start(const CameraCommandOptions& options);
  // Stops the command (SIGTERM to its process group, SIGKILL after a second) and the reader.
  void stop();

  void request_frame(uint32_t settle_us) override;
  FrameStatus poll_frame(uint8_t* frame) override;

  // Why the camera failed ("" while it works).
  std::string failure() const;
  // The frame last taken as the command sent it (width × height × 3), for --save-frames.
  const std::vector<uint8_t>& last_taken() const { return taken_; }
  const CameraCommandOptions& options() const { return options_; }
  CameraStats stats() const;

 private:
  using Clock = std::chrono::steady_clock;
  void read_frames();
  void fail(const std::string& why);  // with mutex_ held

  CameraCommandOptions options_;
  size_t frame_bytes_ = 0;
  pid_t pid_ = -1;
  int fd_ = -1;
  std::thread reader_;
  std::atomic<bool> stopping_{false};

  mutable std::mutex mutex_;  // guards everything below
  std::vector<uint8_t> newest_;
  uint64_t newest_seq_ = 0;  // 0: none yet
  bool newest_suspect_ = false;
  std::vector<double> recent_gaps_;  // the last 32 frame intervals, ms
  Clock::time_point newest_at_{};
  std::string failure_;
  CameraStats stats_;

  // The capture's side (controller thread only).
  std::vector<uint8_t> taken_;
  uint64_t taken_seq_ = 0;
  Clock::time_point requested_at_{};
  Clock::time_point not_before_{};
  bool requested_ = false;
};

// "160x120" → 160, 120 (1..4096 each); false if malformed.
bool parse_frame_size(const std::string& text, int* width, int* height);

}  // namespace curio::app::host
