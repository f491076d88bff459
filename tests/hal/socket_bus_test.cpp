// The socket backends' shared receive path, over a datagram socketpair with a test decoder:
// batched reads past one recvmmsg chunk, consumed datagrams, receive_wait's single wait and
// its re-wait, the receive-timeout setting, wait_readable, and the recover/poll-error hooks
// (a connected UDP socket whose peer port is closed).
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <chrono>
#include <memory>
#include <thread>
#include <utility>
#include <vector>

#include "hal/linux/socket_bus.hpp"

using namespace curio::hal;

namespace {

// Datagrams: 'F' id (a frame) or 'C' id (a control message, consumed); anything else is
// malformed (counted in errors).
constexpr uint8_t kFrame = 'F';
constexpr uint8_t kControl = 'C';

class TestSocketBus final : public SocketBus {
 public:
  explicit TestSocketBus(int fd) : SocketBus(fd, RxLayout{3, 0, 0}, nullptr) {}

  bool recover_result = false;
  bool poll_error_readable = true;
  std::vector<int> recovered;  // errno values recover() saw

  CanStatus set_filters(const CanFilter*, size_t) override { return CanStatus::kOk; }
  bool carries_fd() const override { return true; }
  uint64_t rcvtimeo_us() const {
    timeval tv{};
    socklen_t len = sizeof(tv);
    getsockopt(fd(), SOL_SOCKET, SO_RCVTIMEO, &tv, &len);
    return static_cast<uint64_t>(tv.tv_sec) * 1000000u + static_cast<uint64_t>(tv.tv_usec);
  }

 protected:
  CanStatus transmit(const CanFrame* frames, size_t count, size_t* sent) override {
    *sent = 0;
    for (; *sent < count; ++*sent) {
      const uint8_t d[2] = {kFrame, static_cast<uint8_t>(frames[*sent].id)};
      if (::send(fd(), d, sizeof(d), MSG_DONTWAIT) != 2) return CanStatus::kWouldBlock;
    }
    return CanStatus::kOk;
  }
  bool supports(const CanFrame&) const override { return true; }
  bool decode(const msghdr&, const uint8_t* data, size_t size, CanFrame* out) override {
    if (size != 2 || (data[0] != kFrame && data[0] != kControl)) {
      ++stats_.errors;
      return false;
    }
    if (data[0] == kControl) return false;
    out->id = data[1];
    return true;
  }
  bool recover(int err) override {
    recovered.push_back(err);
    return recover_result;
  }
  bool on_poll_error() override {
    if (poll_error_readable) return true;
    int err = 0;
    socklen_t len = sizeof(err);
    getsockopt(fd(), SOL_SOCKET, SO_ERROR, &err, &len);  // takes the error
    return false;
  }
};

// A bus on one end of a datagram socketpair; the test writes datagrams to the other end.
struct Pair {
  Pair() {
    int fds[2];
    EXPECT_EQ(socketpair(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0, fds), 0);
    bus = std::make_unique<TestSocketBus>(fds[0]);
    peer = fds[1];
  }
  ~Pair() { close(peer); }
  void put(uint8_t kind, uint8_t id) const {
    const uint8_t d[2] = {kind, id};
    EXPECT_EQ(send(peer, d, sizeof(d), 0), 2);
  }
  std::unique_ptr<TestSocketBus> bus;
  int peer = -1;
};

uint64_t elapsed_us(std::chrono::steady_clock::time_point since) {
  return static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::microseconds>(
                                   std::chrono::steady_clock::now() - since)
                                   .count());
}

// receive_wait (up to 5 s) while another thread writes `datagrams` (kind, id), 15 ms apart.
CanStatus receive_wait_while(Pair& p, const std::vector<std::pair<uint8_t, uint8_t>>& datagrams,
                             CanFrame* out, size_t* n) {
  std::thread writer([&] {
    for (const auto& [kind, id] : datagrams) {
      std::this_thread::sleep_for(std::chrono::milliseconds(15));
      p.put(kind, id);
    }
  });
  const CanStatus s = p.bus->receive_wait(out, 2, n, 5'000'000);
  writer.join();
  return s;
}

// A bus whose connected UDP socket has a pending "port unreachable" error.
std::unique_ptr<TestSocketBus> bus_with_refused_peer() {
  const int fd = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  EXPECT_EQ(bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)), 0);  // a free port
  socklen_t len = sizeof(a);
  EXPECT_EQ(getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len), 0);
  // Our own port, closed after connecting: a port nobody listens on.
  const int gone = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  sockaddr_in g = a;
  g.sin_port = 0;
  EXPECT_EQ(bind(gone, reinterpret_cast<sockaddr*>(&g), sizeof(g)), 0);
  len = sizeof(g);
  EXPECT_EQ(getsockname(gone, reinterpret_cast<sockaddr*>(&g), &len), 0);
  close(gone);
  EXPECT_EQ(connect(fd, reinterpret_cast<sockaddr*>(&g), sizeof(g)), 0);
  const uint8_t d[2] = {kFrame, 1};
  EXPECT_EQ(send(fd, d, sizeof(d), 0), 2);
  // The ICMP error comes back through the loopback at once; wait until it is pending.
  pollfd pf{fd, 0, 0};
  EXPECT_EQ(poll(&pf, 1, 1000), 1);
  EXPECT_TRUE(pf.revents & POLLERR);
  auto bus = std::make_unique<TestSocketBus>(fd);
  return bus;
}

}  // namespace

TEST(SocketBus, ReceiveBatchOnAnEmptySocketIsEmpty) {
  Pair p;
  size_t n = 7;
  CanFrame out[4];
  EXPECT_EQ(p.bus->receive_batch(out, 4, &n), CanStatus::kEmpty);
  EXPECT_EQ(n, 0u);
  EXPECT_EQ(p.bus->stats().errors, 0u);
}

TEST(SocketBus, ReadsPastOneChunkInOrderAndSkipsConsumedDatagrams) {
  Pair p;
  constexpr size_t kFrames = SocketBus::kRxChunk + 36;
  for (size_t i = 0; i < kFrames; ++i) {
    if (i % 10 == 0) p.put(kControl, 0);
    p.put(kFrame, static_cast<uint8_t>(i));
  }
  p.put('?', 0);  // malformed
  std::vector<CanFrame> out(kFrames + 20);
  size_t n = 0;
  ASSERT_EQ(p.bus->receive_batch(out.data(), out.size(), &n), CanStatus::kOk);
  ASSERT_EQ(n, kFrames);
  for (size_t i = 0; i < kFrames; ++i) EXPECT_EQ(out[i].id, static_cast<uint32_t>(i));
  EXPECT_EQ(p.bus->stats().rx_frames, kFrames);
  EXPECT_EQ(p.bus->stats().errors, 1u);
  EXPECT_EQ(p.bus->receive_batch(out.data(), out.size(), &n), CanStatus::kEmpty);
}

TEST(SocketBus, ReceiveBatchStopsAtCapacity) {
  Pair p;
  for (uint8_t i = 0; i < 5; ++i) p.put(kFrame, i);
  CanFrame out[3];
  size_t n = 0;
  ASSERT_EQ(p.bus->receive_batch(out, 3, &n), CanStatus::kOk);
  ASSERT_EQ(n, 3u);
  EXPECT_EQ(out[2].id, 2u);
  ASSERT_EQ(p.bus->receive_batch(out, 3, &n), CanStatus::kOk);
  ASSERT_EQ(n, 2u);
  EXPECT_EQ(out[0].id, 3u);
  EXPECT_EQ(out[1].id, 4u);
}

TEST(SocketBus, ReceiveWaitTimesOutAfterItsTimeoutAndSetsTheReceiveTimeout) {
  Pair p;
  CanFrame out[2];
  size_t n = 9;
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(p.bus->receive_wait(out, 2, &n, 30'000), CanStatus::kTimeout);
  EXPECT_GE(elapsed_us(t0), 25'000u);
  EXPECT_EQ(n, 0u);
  // The kernel keeps the receive timeout in jiffies (1-10 ms), rounded up.
  EXPECT_GE(p.bus->rcvtimeo_us(), 30'000u);
  EXPECT_LE(p.bus->rcvtimeo_us(), 40'000u);
  // receive_batch never blocks, whatever the receive timeout.
  const auto t1 = std::chrono::steady_clock::now();
  EXPECT_EQ(p.bus->receive_batch(out, 2, &n), CanStatus::kEmpty);
  EXPECT_LT(elapsed_us(t1), 20'000u);
}

TEST(SocketBus, ReceiveWaitReturnsAFrameThatArrivesDuringTheWait) {
  Pair p;
  CanFrame out[2];
  size_t n = 0;
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_EQ(receive_wait_while(p, {{kFrame, 42}}, out, &n), CanStatus::kOk);
  ASSERT_EQ(n, 1u);
  EXPECT_EQ(out[0].id, 42u);
  EXPECT_LT(elapsed_us(t0), 2'000'000u);
}

TEST(SocketBus, ReceiveWaitGoesOnWaitingAfterOnlyConsumedDatagrams) {
  Pair p;
  CanFrame out[2];
  size_t n = 0;
  ASSERT_EQ(receive_wait_while(p, {{kControl, 0}, {kFrame, 7}}, out, &n), CanStatus::kOk)
      << "a consumed datagram does not end the wait";
  ASSERT_EQ(n, 1u);
  EXPECT_EQ(out[0].id, 7u);

  // Only consumed datagrams: the wait ends in kTimeout, never kEmpty.
  p.put(kControl, 0);
  EXPECT_EQ(p.bus->receive_wait(out, 2, &n, 20'000), CanStatus::kTimeout);
  EXPECT_EQ(n, 0u);
}

TEST(SocketBus, WaitReadable) {
  Pair p;
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(p.bus->wait_readable(20'000), CanStatus::kTimeout);
  EXPECT_GE(elapsed_us(t0), 15'000u);
  p.put(kFrame, 3);
  EXPECT_EQ(p.bus->wait_readable(1'000'000), CanStatus::kOk);
  CanFrame out;
  EXPECT_EQ(p.bus->receive(&out), CanStatus::kOk);
  EXPECT_EQ(out.id, 3u);
}

TEST(SocketBus, SentFramesReachThePeer) {
  Pair p;
  ASSERT_EQ(p.bus->send(CanFrame{5, 0, 0, {}}, p.bus->now_us() + 1'000'000), CanStatus::kOk);
  uint8_t d[4] = {};
  EXPECT_EQ(recv(p.peer, d, sizeof(d), MSG_DONTWAIT), 2);
  EXPECT_EQ(d[0], kFrame);
  EXPECT_EQ(d[1], 5u);
}

TEST(SocketBus, AReadErrorTheBackendRecoversFromIsReadAgain) {
  auto bus = bus_with_refused_peer();
  bus->recover_result = true;
  CanFrame out[2];
  size_t n = 0;
  EXPECT_EQ(bus->receive_batch(out, 2, &n), CanStatus::kEmpty);
  ASSERT_EQ(bus->recovered.size(), 1u);
  EXPECT_EQ(bus->recovered[0], ECONNREFUSED);
  EXPECT_EQ(bus->stats().errors, 0u) << "recovered: not an error";
}

TEST(SocketBus, AReadErrorTheBackendDoesNotRecoverFromIsCounted) {
  auto bus = bus_with_refused_peer();
  CanFrame out[2];
  size_t n = 0;
  EXPECT_EQ(bus->receive_batch(out, 2, &n), CanStatus::kEmpty);
  EXPECT_EQ(bus->recovered.size(), 1u);
  EXPECT_EQ(bus->stats().errors, 1u);
}

TEST(SocketBus, APollErrorIsReadableOnlyIfTheBackendSaysSo) {
  auto readable = bus_with_refused_peer();
  EXPECT_EQ(readable->wait_readable(1'000'000), CanStatus::kOk);
  auto handled = bus_with_refused_peer();
  handled->poll_error_readable = false;
  EXPECT_EQ(handled->wait_readable(20'000), CanStatus::kTimeout);
}
