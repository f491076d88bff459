#include "sim/serve/camera_stream.hpp"

#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <vector>

#include "firmware/protocol/arm_messages.hpp"
#include "sim/render.hpp"

namespace curio::sim::serve {

CameraStream::~CameraStream() {
  for (Reader& r : readers_) ::close(r.fd);
  if (listen_fd_ >= 0) {
    ::close(listen_fd_);
    ::unlink(options_.socket_path.c_str());
  }
}

std::string CameraStream::open(const CameraStreamOptions& options) {
  options_ = options;
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  if (options.socket_path.empty() || options.socket_path.size() >= sizeof addr.sun_path)
    return "the socket path must be 1 to " + std::to_string(sizeof addr.sun_path - 1) + " bytes";
  std::memcpy(addr.sun_path, options.socket_path.c_str(), options.socket_path.size());
  struct stat st {};
  if (::stat(options.socket_path.c_str(), &st) == 0) {
    if (!S_ISSOCK(st.st_mode)) return options.socket_path + " exists and is not a socket";
    ::unlink(options.socket_path.c_str());
  }
  listen_fd_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (listen_fd_ < 0) return std::string("socket: ") + std::strerror(errno);
  if (::bind(listen_fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0 ||
      ::listen(listen_fd_, 4) != 0) {
    const std::string why = std::strerror(errno);
    ::close(listen_fd_);
    listen_fd_ = -1;
    return options.socket_path + ": " + why;
  }
  period_us_ = static_cast<uint64_t>(std::llround(1e6 / options.fps));
  image_.resize(static_cast<size_t>(options.width) * static_cast<size_t>(options.height) * 3);
  bytes_.resize(image_.size());
  return "";
}

void CameraStream::flush(Reader& r) {
  while (r.pending > 0) {
    const ssize_t n = ::send(r.fd, r.frame.data() + (r.frame.size() - r.pending), r.pending,
                             MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n > 0) {
      r.pending -= static_cast<size_t>(n);
      if (r.pending == 0) ++counters_.frames_sent;
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return;
    ::close(r.fd);  // the reader went away
    r.fd = -1;
    return;
  }
}

uint64_t CameraStream::tick(uint64_t now_us, const SceneState& scene) {
  if (listen_fd_ < 0) return 1'000'000;
  for (;;) {
    const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) break;
    // A camera does not queue seconds of old frames: the kernel holds about one frame for a
    // reader (Linux doubles the value), a frame it has no room for is dropped here.
    const int bytes = static_cast<int>(bytes_.size());
    ::setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &bytes, sizeof bytes);
    readers_.push_back(Reader{fd, 0, std::vector<uint8_t>(bytes_.size())});
    ++counters_.readers;
  }
  for (Reader& r : readers_) flush(r);
  std::erase_if(readers_, [](const Reader& r) { return r.fd < 0; });
  if (next_us_ == 0) next_us_ = now_us;
  if (now_us < next_us_) return next_us_ - now_us;
  // A fixed frame rate on the wall clock: frame k at start + k·period (late frames are not
  // made up for: the next is the first period boundary after now).
  while (next_us_ <= now_us) next_us_ += period_us_;
  render_scene(scene.ball, scene.distractor, options_.width, options_.height, image_.data());
  for (size_t i = 0; i < image_.size(); ++i) bytes_[i] = protocol::camera_pixel(image_[i]);
  ++counters_.frames_rendered;
  for (Reader& r : readers_) {
    if (r.pending > 0) {
      ++counters_.frames_dropped;
      continue;
    }
    r.frame = bytes_;
    r.pending = r.frame.size();
    flush(r);
  }
  std::erase_if(readers_, [](const Reader& r) { return r.fd < 0; });
  return next_us_ - now_us;
}

}  // namespace curio::sim::serve
