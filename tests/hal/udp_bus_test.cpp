// The UDP bus on 127.0.0.1: the bus contract, the datagram codec, foreign traffic, a full port
// range, and real separate processes (curio-can echo) on one bus.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include "tests/hal/bus_contract.hpp"
#include "hal/linux/open_bus.hpp"
#include "hal/linux/udp_bus.hpp"

extern char** environ;

using namespace curio::hal;
using namespace curio::hal::test;

namespace {

// `classic`: every endpoint opened with classic=1.
BusBackend udp_backend(bool classic) {
  return {classic ? "udp_classic" : "udp",
          [classic] {
            const uint16_t base = free_udp_base(8);
            return std::function<std::unique_ptr<CanBus>(std::string*)>(
                [base, classic](std::string* why) -> std::unique_ptr<CanBus> {
                  return open_bus("udp:127.0.0.1:" + std::to_string(base) +
                                      (classic ? "?classic=1" : ""),
                                  why);
                });
          },
          false, !classic};
}

// A child process running `curio-can ARGS...`; killed on destruction.
class Child {
 public:
  explicit Child(std::vector<std::string> args) {
    args.insert(args.begin(), CURIO_CAN_TOOL);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    if (posix_spawn(&pid_, CURIO_CAN_TOOL, nullptr, nullptr, argv.data(), environ) != 0) pid_ = -1;
  }
  ~Child() {
    if (pid_ > 0) {
      kill(pid_, SIGTERM);
      waitpid(pid_, nullptr, 0);
    }
  }
  bool ok() const { return pid_ > 0; }

 private:
  pid_t pid_ = -1;
};

// Pings until an echo process answers (process start-up), then drains the extra echoes.
bool wait_for_echoes(CanBus& bus, size_t peers) {
  const CanFrame ping = frame_of(0x7F0, 1);
  for (int i = 0; i < 300; ++i) {
    bus.send(ping, bus.now_us() + 100'000);
    if (collect(bus, peers, 20'000).size() >= peers) {
      while (!collect(bus, 1, 50'000).empty()) {
      }
      return true;
    }
  }
  return false;
}

}  // namespace

INSTANTIATE_TEST_SUITE_P(Udp, BusContract, ::testing::Values(udp_backend(false), udp_backend(true)),
                         [](const auto& info) { return info.param.name; });

TEST(UdpDatagram, RoundTripsAndRejectsMalformedInput) {
  uint8_t buf[kUdpHeaderBytes + 64];
  const CanFrame f = frame_of(0x18DAF120u, 64, true, true);
  const size_t n = encode_udp_datagram(f, buf);
  EXPECT_EQ(n, kUdpHeaderBytes + 64);
  CanFrame g;
  ASSERT_TRUE(decode_udp_datagram(buf, n, &g));
  EXPECT_TRUE(same_frame(f, g));
  EXPECT_FALSE(decode_udp_datagram(buf, n - 1, &g)) << "truncated";
  buf[0] = 'X';
  EXPECT_FALSE(decode_udp_datagram(buf, n, &g)) << "bad magic";
  buf[0] = kUdpMagic;
  buf[3] = 13;
  EXPECT_FALSE(decode_udp_datagram(buf, kUdpHeaderBytes + 13, &g)) << "not an FD length";
}

TEST(UdpBus, ForeignDatagramsAreDroppedAndCounted) {
  const uint16_t base = free_udp_base(4);
  std::string why;
  auto bus = UdpBus::open(base, 4, &why);
  ASSERT_TRUE(bus) << why;
  // A stranger outside the port range sends a well-formed frame and some garbage.
  const int s = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(bus->port());
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  uint8_t buf[kUdpHeaderBytes + 64];
  const size_t n = encode_udp_datagram(frame_of(0x10, 8), buf);
  sendto(s, buf, n, 0, reinterpret_cast<sockaddr*>(&to), sizeof(to));
  sendto(s, "garbage", 7, 0, reinterpret_cast<sockaddr*>(&to), sizeof(to));
  close(s);
  EXPECT_TRUE(collect(*bus, 1, 100'000).empty());
  EXPECT_EQ(bus->stats().errors, 2u);
}

TEST(UdpBus, FullPortRangeIsAClearError) {
  const uint16_t base = free_udp_base(2);
  std::string why;
  auto a = UdpBus::open(base, 2, &why);
  auto b = UdpBus::open(base, 2, &why);
  ASSERT_TRUE(a && b) << why;
  EXPECT_EQ(UdpBus::open(base, 2, &why), nullptr);
  EXPECT_NE(why.find("in use"), std::string::npos) << why;
}

TEST(UdpBus, SeparateProcessesShareTheBus) {
  const uint16_t base = free_udp_base(8);
  const std::string url = "udp:127.0.0.1:" + std::to_string(base);
  std::string why;
  auto bus = open_bus(url, &why);
  ASSERT_TRUE(bus) << why;
  // Two echo processes: every even-id frame comes back twice with id|1.
  Child echo1({"echo", "--bus", url, "-t", "10000"});
  Child echo2({"echo", "--bus", url, "-t", "10000"});
  ASSERT_TRUE(echo1.ok() && echo2.ok());
  const CanFilter echoes{0x001, 0x001, IdType::kAny};
  bus->set_filters(&echoes, 1);
  ASSERT_TRUE(wait_for_echoes(*bus, 2)) << "echo processes did not answer";
  std::vector<CanFrame> sent;
  for (int i = 0; i < 100; ++i) {
    sent.push_back(frame_of(0x18DAF120u, 64, true, true, static_cast<uint8_t>(i)));
  }
  ASSERT_EQ(bus->send_batch(sent.data(), sent.size(), bus->now_us() + 1'000'000, nullptr),
            CanStatus::kOk);
  auto got = collect(*bus, 2 * sent.size(), 2'000'000);
  ASSERT_EQ(got.size(), 2 * sent.size());
  // Each echo's answers arrive in order; count per payload.
  std::vector<int> seen(sent.size(), 0);
  for (const auto& f : got) {
    EXPECT_EQ(f.id, 0x18DAF121u);
    EXPECT_EQ(f.len, 64);
    const int i = static_cast<uint8_t>(f.data[0] - 1);
    ASSERT_LT(i, 100);
    CanFrame expect = sent[static_cast<size_t>(i)];
    expect.id |= 1u;
    EXPECT_TRUE(same_frame(f, expect));
    ++seen[static_cast<size_t>(i)];
  }
  for (int c : seen) EXPECT_EQ(c, 2);
}
