#include "host_tools/controller/camera_command.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/ioctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <algorithm>

#include "host_tools/experiment/camera_resample.hpp"

namespace curio::app::host {

namespace {

double ms_between(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

std::string exit_text(int status) {
  if (WIFEXITED(status)) return "exited with status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return std::string("was killed by signal ") + strsignal(WTERMSIG(status));
  return "ended";
}

}  // namespace

bool parse_frame_size(const std::string& text, int* width, int* height) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X'))
    return false;
  if (w < 1 || w > 4096 || h < 1 || h > 4096) return false;
  *width = w;
  *height = h;
  return true;
}

CameraCommand::~CameraCommand() { stop(); }

std::string CameraCommand::start(const CameraCommandOptions& options) {
  options_ = options;
  frame_bytes_ = static_cast<size_t>(options.width) * static_cast<size_t>(options.height) * 3;
  int out[2];
  if (pipe2(out, O_CLOEXEC) != 0) return std::string("cannot make a pipe: ") + std::strerror(errno);
  const int log = options.log_path.empty()
                      ? open("/dev/null", O_WRONLY | O_CLOEXEC)
                      : open(options.log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (log < 0) {
    close(out[0]);
    close(out[1]);
    return "cannot write the camera's log " + options.log_path + ": " + std::strerror(errno);
  }
  const pid_t pid = fork();
  if (pid < 0) {
    close(out[0]);
    close(out[1]);
    close(log);
    return std::string("cannot start the camera command: fork: ") + std::strerror(errno);
  }
  if (pid == 0) {  // the child: its own process group (stopped as one), stdout → the pipe
    setpgid(0, 0);
    const int in = open("/dev/null", O_RDONLY);
    if (in >= 0) dup2(in, 0);
    dup2(out[1], 1);
    dup2(log, 2);
    signal(SIGPIPE, SIG_DFL);
    execl("/bin/sh", "sh", "-c", options.command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  setpgid(pid, pid);  // also here: no race with the child's own call
  close(out[1]);
  close(log);
  pid_ = pid;
  fd_ = out[0];
  stopping_ = false;
  reader_ = std::thread([this] { read_frames(); });
  // The first whole frame, or why none comes.
  const auto deadline = Clock::now() + std::chrono::milliseconds(options.start_timeout_ms);
  const std::string log_hint =
      options.log_path.empty() ? "" : " (its messages: " + options.log_path + ")";
  for (;;) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (newest_seq_ > 0) return "";
      if (!failure_.empty()) return failure_ + log_hint;
    }
    if (Clock::now() >= deadline) {
      stop();
      return "no whole " + std::to_string(options.width) + "x" + std::to_string(options.height) +
             " frame within " + std::to_string(options.start_timeout_ms) +
             " ms of starting the command (--camera-start-timeout)" + log_hint;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

void CameraCommand::fail(const std::string& why) {
  if (failure_.empty()) failure_ = why;
}

void CameraCommand::read_frames() {
  std::vector<uint8_t> frame(frame_bytes_);
  std::vector<uint8_t> in(64 * 1024);
  size_t in_at = 0, in_end = 0;
  uint64_t whole = 0;
  Clock::time_point last = Clock::now();
  const std::string size_text = std::to_string(options_.width) + "x" + std::to_string(options_.height);
  // Bytes from the command: > 0 available in in[in_at, in_end), 0 the stream ended, -1 stop
  // (stopping, a read error or a stall, failure set).
  const auto fill = [&]() -> int {
    while (in_at == in_end) {
      if (stopping_.load()) return -1;
      pollfd p{fd_, POLLIN, 0};
      const int ready = ::poll(&p, 1, 50);
      if (ready == 0) {
        // A gap longer than the stall limit after the first frame (the start has its own limit).
        if (whole > 0 && ms_between(last, Clock::now()) > options_.stall_ms) {
          std::lock_guard<std::mutex> lock(mutex_);
          fail("stalled: no frame for " + std::to_string(options_.stall_ms) +
               " ms (--camera-stall) after " + std::to_string(whole) + " frames");
          return -1;
        }
        continue;
      }
      if (ready < 0 && errno == EINTR) continue;
      const ssize_t n = ready < 0 ? -1 : ::read(fd_, in.data(), in.size());
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        std::lock_guard<std::mutex> lock(mutex_);
        fail(std::string("cannot read its output: ") + std::strerror(errno));
        return -1;
      }
      if (n == 0) return 0;
      in_at = 0;
      in_end = static_cast<size_t>(n);
    }
    return 1;
  };
  const auto how_it_ended = [&]() {
    int status = 0;
    for (int i = 0; i < 100; ++i) {
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        return "the command " + exit_text(status);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return std::string("the command's output ended");
  };
  const auto ended = [&](size_t partial, const std::string& where) {
    const std::string how = how_it_ended();
    std::lock_guard<std::mutex> lock(mutex_);
    if (partial > 0)
      fail(how + " after " + std::to_string(whole) + " whole frames and " + std::to_string(partial) +
           " bytes more" + where + ": its frames are not " + size_text + " RGB24 (" +
           std::to_string(frame_bytes_) + " bytes each; --camera-size)");
    else
      fail(how + (whole == 0 ? " before its first frame" : " after " + std::to_string(whole) + " frames"));
  };
  // PPM (P6) header: "P6" width height maxval, separated by whitespace (comments allowed),
  // one whitespace byte before the pixels. "" or what is wrong with it.
  const auto ppm_header = [&](bool* at_end) -> std::string {
    std::string tokens[4];
    int t = 0;
    size_t seen = 0;
    bool comment = false;
    for (;;) {
      const int r = fill();
      if (r <= 0) {
        *at_end = r == 0 && seen == 0;
        return r == 0 ? (seen == 0 ? "" : "a PPM header cut short") : "-";
      }
      const char c = static_cast<char>(in[in_at++]);
      ++seen;
      if (seen > 256) return "not a PPM stream (no P6 header within 256 bytes)";
      if (comment) {
        comment = c != '\n';
        continue;
      }
      if (c == '#') {
        comment = true;
        continue;
      }
      if (c == ' ' || c == '\n' || c == '\r' || c == '\t') {
        if (!tokens[t].empty()) ++t;
        if (t == 4) break;
        continue;
      }
      tokens[t] += c;
    }
    if (tokens[0] != "P6") return "not a PPM (P6) stream";
    if (tokens[1] + "x" + tokens[2] != size_text)
      return "a frame of " + tokens[1] + "x" + tokens[2] + ", not " + size_text + " (--camera-size)";
    if (tokens[3] != "255") return "a PPM frame with maxval " + tokens[3] + " (8-bit RGB needed)";
    return "";
  };
  for (;;) {
    if (options_.ppm) {
      bool at_end = false;
      const std::string bad = ppm_header(&at_end);
      if (bad == "-") return;
      if (at_end) return ended(0, "");
      if (!bad.empty()) {
        std::lock_guard<std::mutex> lock(mutex_);
        fail("frame " + std::to_string(whole + 1) + ": " + bad);
        return;
      }
    }
    size_t got = 0;
    while (got < frame_bytes_) {
      const int r = fill();
      if (r < 0) return;
      if (r == 0) return ended(got, options_.ppm ? " (pixels cut short)" : "");
      const size_t n = std::min(frame_bytes_ - got, in_end - in_at);
      std::memcpy(frame.data() + got, in.data() + in_at, n);
      in_at += n;
      got += n;
    }
    const auto now = Clock::now();
    ++whole;
    // Newest only: a frame with another whole one already behind it (the reader fell behind)
    // is superseded, and never published with a fresh arrival time.
    int queued = 0;
    if (ioctl(fd_, FIONREAD, &queued) == 0 &&
        (in_end - in_at) + static_cast<size_t>(queued) >= frame_bytes_) {
      std::lock_guard<std::mutex> lock(mutex_);
      ++stats_.frames_read;
      ++stats_.frames_superseded;
      continue;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    // A frame that ends an unusually long silence was held up somewhere between the camera and
    // here (a process descheduled, a network hiccup), and so may be one exposed long ago; the
    // frames right behind it (a burst) too. Neither is taken: the next frame on the stream's
    // own rhythm is.
    bool suspect = false;
    if (newest_seq_ > 0) {
      const double gap = ms_between(newest_at_, now);
      if (recent_gaps_.size() >= 8) {
        std::vector<double> sorted(recent_gaps_.begin(), recent_gaps_.end());
        std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
        const double median = sorted[sorted.size() / 2];
        suspect = gap > 3 * median + 5 || gap < 0.25 * median;
      }
      recent_gaps_.push_back(gap);
      if (recent_gaps_.size() > 32) recent_gaps_.erase(recent_gaps_.begin());
      stats_.gap_ms.push_back(gap);
    }
    if (suspect) ++stats_.frames_distrusted;
    newest_suspect_ = suspect;
    newest_.swap(frame);
    frame.resize(frame_bytes_);
    newest_seq_ = whole;
    newest_at_ = now;
    last = now;
    ++stats_.frames_read;
  }
}

void CameraCommand::stop() {
  if (pid_ > 0) kill(-pid_, SIGTERM);
  stopping_ = true;
  if (reader_.joinable()) reader_.join();
  if (pid_ > 0) {
    int status = 0;
    for (int i = 0; i < 100 && waitpid(pid_, &status, WNOHANG) == 0; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (waitpid(pid_, &status, WNOHANG) == 0) {
      kill(-pid_, SIGKILL);
      waitpid(pid_, &status, 0);
    }
    pid_ = -1;
  }
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
}

void CameraCommand::request_frame(uint32_t settle_us) {
  requested_at_ = Clock::now();
  not_before_ = requested_at_ + std::chrono::microseconds(settle_us);
  requested_ = true;
}

FrameStatus CameraCommand::poll_frame(uint8_t* frame) {
  const auto now = Clock::now();
  std::lock_guard<std::mutex> lock(mutex_);
  if (!failure_.empty()) return FrameStatus::kFailed;
  if (!requested_ || newest_seq_ <= taken_seq_ || newest_at_ < not_before_ || newest_suspect_)
    return FrameStatus::kPending;
  // Fresh: arrived after the settle time, and not taken before.
  taken_ = newest_;
  taken_seq_ = newest_seq_;
  ++stats_.frames_taken;
  stats_.sequence.push_back(newest_seq_);
  stats_.settle_ms = ms_between(requested_at_, not_before_);
  stats_.wait_ms.push_back(ms_between(requested_at_, newest_at_));
  stats_.age_ms.push_back(ms_between(newest_at_, now));
  requested_ = false;
  lab::resample_to_camera(taken_.data(), options_.width, options_.height, frame);
  return FrameStatus::kFresh;
}

std::string CameraCommand::failure() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return failure_;
}

CameraStats CameraCommand::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

}  // namespace curio::app::host
