// curio-can slcan-bridge (slcan_bridge.hpp): one poll() loop over the serial descriptor and
// the bus socket.
#include "host_tools/can_tools/slcan_bridge.hpp"

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <deque>
#include <thread>
#include <vector>

#include "hal/linux/open_bus.hpp"
#include "hal/linux/socket_bus.hpp"

namespace curio::hal::tools {

namespace {

volatile std::sig_atomic_t g_stop = 0;  // the signal that stops the bridge
void on_signal(int sig) {
  g_stop = sig;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int connect_unix(const std::string& path, double timeout_s) {
  const auto t0 = std::chrono::steady_clock::now();
  for (;;) {
    const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) return -1;
    sockaddr_un a{};
    a.sun_family = AF_UNIX;
    if (path.size() >= sizeof a.sun_path) {
      ::close(fd);
      errno = ENAMETOOLONG;
      return -1;
    }
    std::memcpy(a.sun_path, path.c_str(), path.size() + 1);
    if (::connect(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) == 0) return fd;
    const int err = errno;
    ::close(fd);
    if ((err != ENOENT && err != ECONNREFUSED) || seconds_since(t0) > timeout_s) {
      errno = err;
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

// The serial side's descriptor, non-blocking; -1 with a message on failure.
int open_serial(const SlcanBridgeOptions& o) {
  int fd = -1;
  const std::string& s = o.serial;
  if (s.rfind("unix:", 0) == 0) {
    fd = connect_unix(s.substr(5), o.connect_timeout_s);
    if (fd < 0)
      std::fprintf(stderr, "slcan-bridge: connect %s: %s\n", s.c_str(), std::strerror(errno));
  } else if (s == "pty") {
    int slave = -1;
    char name[128] = {};
    if (::openpty(&fd, &slave, name, nullptr, nullptr) != 0) {
      std::fprintf(stderr, "slcan-bridge: openpty: %s\n", std::strerror(errno));
      return -1;
    }
    termios t{};
    ::tcgetattr(slave, &t);
    ::cfmakeraw(&t);
    ::tcsetattr(slave, TCSANOW, &t);
    // The slave stays open here too, so the pty survives a peer that closes and reopens it.
    std::printf("slcan-bridge: serial on %s\n", name);
    std::fflush(stdout);
  } else if (s.rfind("fd:", 0) == 0) {
    fd = std::atoi(s.c_str() + 3);
    if (fd < 0 || ::fcntl(fd, F_GETFD) < 0) {
      std::fprintf(stderr, "slcan-bridge: %s is not an open descriptor\n", s.c_str());
      return -1;
    }
  } else {
    std::fprintf(stderr, "slcan-bridge: bad --serial '%s' (unix:PATH, pty or fd:N)\n", s.c_str());
    return -1;
  }
  if (fd >= 0) ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
  return fd;
}

struct Stats {
  uint64_t serial_to_bus = 0;   // frames
  uint64_t bus_to_serial = 0;   // frames
  uint64_t bytes_in = 0;        // serial bytes read
  uint64_t bytes_out = 0;       // serial bytes written
  uint64_t unencodable = 0;     // bus frames with no SLCAN form in this mode
  uint64_t bus_refused = 0;     // serial frames the bus would not take
  size_t max_queued_lines = 0;  // bus → serial backlog
};

void print_stats(const Stats& s, const protocol::SlcanCounters& c, const CanStats& bus,
                 double secs) {
  std::fprintf(stderr,
               "slcan-bridge: %.1f s: serial→bus %llu frames (%.0f/s, %llu bytes), bus→serial "
               "%llu frames (%.0f/s, %llu bytes); lines: %u commands, %u malformed (id %u, "
               "length %u, hex %u, FD on classic %u, overlong %u); %llu bus frames without an "
               "SLCAN form, %llu refused by the bus, bus tx timed out %llu; most lines queued "
               "%zu\n",
               secs, static_cast<unsigned long long>(s.serial_to_bus),
               secs > 0 ? s.serial_to_bus / secs : 0.0, static_cast<unsigned long long>(s.bytes_in),
               static_cast<unsigned long long>(s.bus_to_serial),
               secs > 0 ? s.bus_to_serial / secs : 0.0,
               static_cast<unsigned long long>(s.bytes_out), c.commands, c.malformed(), c.bad_id,
               c.bad_length, c.bad_hex, c.unsupported, c.overlong,
               static_cast<unsigned long long>(s.unencodable),
               static_cast<unsigned long long>(s.bus_refused),
               static_cast<unsigned long long>(bus.tx_timedout), s.max_queued_lines);
}

}  // namespace

int run_slcan_bridge(const SlcanBridgeOptions& o) {
  std::string error;
  auto bus = open_bus(o.bus, &error);
  if (!bus) {
    std::fprintf(stderr, "slcan-bridge: %s\n", error.c_str());
    return 1;
  }
  if (o.mode == protocol::SlcanMode::kClassic && bus->carries_fd()) {
    // Not an error (classic frames cross), but the arm protocol's FD profile would not.
    std::fprintf(stderr,
                 "slcan-bridge: note: the link is classic (no --fd) but %s carries CAN FD; "
                 "endpoints there run the FD profile, whose ground truth and image frames this "
                 "link cannot carry: add classic=1 to their bus URLs (docs/can.md)\n",
                 o.bus.c_str());
  }
  const int serial = open_serial(o);
  if (serial < 0) return 1;
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::signal(SIGPIPE, SIG_IGN);

  const auto* socket_bus = dynamic_cast<const SocketBus*>(bus.get());
  const int bus_fd = socket_bus != nullptr ? socket_bus->pollable_fd() : -1;
  protocol::SlcanLineAssembler assembler(o.mode);
  std::deque<std::string> lines;  // bus → serial, whole lines
  size_t line_at = 0;             // bytes of lines.front() already written
  Stats st;
  std::vector<CanFrame> to_bus;
  const auto t0 = std::chrono::steady_clock::now();
  auto last_stats = t0;
  double tokens = o.burst;  // pacing bucket, lines
  auto last_refill = t0;
  bool serial_open = true;
  uint8_t buf[4096];

  while (serial_open && g_stop == 0) {
    // Pacing: lines may be written while tokens last; otherwise wake when one is due.
    const auto now = std::chrono::steady_clock::now();
    if (o.max_fps > 0) {
      tokens = std::min<double>(
          o.burst, tokens + std::chrono::duration<double>(now - last_refill).count() * o.max_fps);
      last_refill = now;
    }
    const bool may_write = !lines.empty() && (o.max_fps <= 0 || tokens >= 1.0 || line_at > 0);
    const CanStats bs = bus->stats();
    const bool bus_backlog = bs.tx_frames + bs.tx_timedout + st.bus_refused < st.serial_to_bus;
    int timeout_ms = 100;
    if (bus_backlog || bus_fd < 0) timeout_ms = 1;
    if (!lines.empty() && !may_write) timeout_ms = 1;

    pollfd p[2] = {{serial, static_cast<short>(POLLIN | (may_write ? POLLOUT : 0)), 0},
                   {bus_fd, POLLIN, 0}};
    const int r = ::poll(p, bus_fd >= 0 ? 2 : 1, timeout_ms);
    if (r < 0 && errno != EINTR) {
      std::fprintf(stderr, "slcan-bridge: poll: %s\n", std::strerror(errno));
      break;
    }

    // Serial → bus.
    if (r > 0 && (p[0].revents & (POLLIN | POLLHUP | POLLERR)) != 0) {
      const ssize_t n = ::read(serial, buf, sizeof buf);
      if (n == 0 || (n < 0 && errno != EAGAIN && errno != EINTR && errno != EIO)) {
        serial_open = false;
      } else if (n < 0 && errno == EIO) {
        // A pty whose peer has not opened it yet (or closed it): keep waiting.
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      } else if (n > 0) {
        st.bytes_in += static_cast<uint64_t>(n);
        to_bus.clear();
        for (ssize_t i = 0; i < n; ++i) {
          CanFrame f;
          if (assembler.push(buf[i], &f) == protocol::SlcanStatus::kFrame) to_bus.push_back(f);
        }
        if (!to_bus.empty()) {
          size_t done = 0;
          const uint64_t deadline = bus->now_us() + 100'000;
          while (done < to_bus.size()) {
            size_t k = 0;
            const CanStatus s =
                hal::send_all(*bus, to_bus.data() + done, to_bus.size() - done, deadline, &k);
            done += k;
            st.serial_to_bus += k;
            if (s != CanStatus::kOk) {  // skip the frame the bus refused
              ++st.bus_refused;
              ++st.serial_to_bus;
              ++done;
            }
          }
        }
      }
    }

    // Bus → serial: drain everything the bus has (its socket buffer must not fill).
    CanFrame batch[64];
    size_t got = 0;
    while (bus->receive_batch(batch, 64, &got) == CanStatus::kOk) {
      for (size_t i = 0; i < got; ++i) {
        char line[protocol::kSlcanMaxLine];
        const size_t len = protocol::slcan_encode(batch[i], o.mode, line, sizeof line);
        if (len == 0) {
          ++st.unencodable;
          continue;
        }
        lines.emplace_back(line, len);
        ++st.bus_to_serial;
      }
    }
    st.max_queued_lines = std::max(st.max_queued_lines, lines.size());

    // Write queued lines while the serial side takes them (and the pacing allows).
    while (!lines.empty()) {
      if (o.max_fps > 0 && line_at == 0) {
        if (tokens < 1.0) break;
        tokens -= 1.0;
      }
      const std::string& l = lines.front();
      const ssize_t w = ::write(serial, l.data() + line_at, l.size() - line_at);
      if (w < 0) {
        if (errno == EAGAIN || errno == EINTR || errno == EIO) {
          if (o.max_fps > 0 && line_at == 0) tokens += 1.0;  // not written after all
          break;
        }
        std::fprintf(stderr, "slcan-bridge: write: %s\n", std::strerror(errno));
        serial_open = false;
        break;
      }
      st.bytes_out += static_cast<uint64_t>(w);
      line_at += static_cast<size_t>(w);
      if (line_at == l.size()) {
        lines.pop_front();
        line_at = 0;
      }
    }

    if (o.stats_every_s > 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - last_stats).count() >=
            o.stats_every_s) {
      last_stats = std::chrono::steady_clock::now();
      print_stats(st, assembler.counters(), bus->stats(), seconds_since(t0));
    }
  }
  // Let the bus backlog go out before the process (and its socket) ends.
  for (int i = 0; i < 100; ++i) {
    const CanStats bs = bus->stats();
    if (bs.tx_frames + bs.tx_timedout + st.bus_refused >= st.serial_to_bus) break;
    bus->wait_readable(1000);
  }
  print_stats(st, assembler.counters(), bus->stats(), seconds_since(t0));
  ::close(serial);
  return g_stop != 0 ? 128 + g_stop : 0;  // 130 after SIGINT, 143 after SIGTERM
}

}  // namespace curio::hal::tools
