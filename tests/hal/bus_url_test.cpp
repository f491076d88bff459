// Bus URLs: what each scheme accepts, and that bad URLs fail with a message saying why.
#include <gtest/gtest.h>

#include "hal/linux/open_bus.hpp"

using namespace curio::hal;

TEST(BusUrl, ParsesEveryScheme) {
  BusUrl u;
  std::string err;
  ASSERT_TRUE(parse_bus_url("loopback", &u, &err)) << err;
  EXPECT_EQ(u.kind, BusUrl::Kind::kLoopback);
  EXPECT_EQ(u.name, "default");
  ASSERT_TRUE(parse_bus_url("loopback:arm", &u, &err)) << err;
  EXPECT_EQ(u.name, "arm");
  ASSERT_TRUE(parse_bus_url("socketcan:vcan0", &u, &err)) << err;
  EXPECT_EQ(u.kind, BusUrl::Kind::kSocketCan);
  EXPECT_EQ(u.name, "vcan0");
  EXPECT_FALSE(u.error_frames);
  ASSERT_TRUE(parse_bus_url("socketcan:can1?errors=1", &u, &err)) << err;
  EXPECT_TRUE(u.error_frames);
  ASSERT_TRUE(parse_bus_url("udp:127.0.0.1:47000", &u, &err)) << err;
  EXPECT_EQ(u.kind, BusUrl::Kind::kUdp);
  EXPECT_EQ(u.port, 47000);
  EXPECT_EQ(u.ports, 8u);
  ASSERT_TRUE(parse_bus_url("udp:127.0.0.1:47000?ports=3", &u, &err)) << err;
  EXPECT_EQ(u.ports, 3u);
  EXPECT_FALSE(u.classic);
  // classic=1: a classic-only endpoint; options joined by '&' in any order.
  ASSERT_TRUE(parse_bus_url("udp:127.0.0.1:47000?classic=1&ports=3", &u, &err)) << err;
  EXPECT_TRUE(u.classic);
  EXPECT_EQ(u.ports, 3u);
  ASSERT_TRUE(parse_bus_url("loopback:arm?classic=1", &u, &err)) << err;
  EXPECT_TRUE(u.classic);
}

TEST(BusUrl, ClassicEndpointsCarryNoFd) {
  std::string err;
  auto a = open_bus("loopback:classic_url_test?classic=1", &err);
  auto b = open_bus("loopback:classic_url_test", &err);
  ASSERT_TRUE(a && b) << err;
  EXPECT_FALSE(a->carries_fd());
  EXPECT_TRUE(b->carries_fd());
}

TEST(BusUrl, BadUrlsSayWhatIsWrong) {
  const std::pair<const char*, const char*> cases[] = {
      {"", "unknown scheme"},
      {"can0", "unknown scheme"},
      {"socketcan:", "interface name"},
      {"socketcan:averyveryverylongname", "interface name"},
      {"socketcan:vcan0?errors=2", "errors=0 or errors=1"},
      {"udp:127.0.0.1", "127.0.0.1:PORT"},
      {"udp:0.0.0.0:5000", "only runs on 127.0.0.1"},
      {"udp:localhost:5000", "only runs on 127.0.0.1"},
      {"udp:192.168.1.2:5000", "only runs on 127.0.0.1"},
      {"udp:127.0.0.1:0", "PORT must be"},
      {"udp:127.0.0.1:70000", "PORT must be"},
      {"udp:127.0.0.1:12x", "PORT must be"},
      {"udp:127.0.0.1:65535", "exceeds 65535"},
      {"udp:127.0.0.1:5000?ports=1", "ports=N"},
      {"udp:127.0.0.1:5000?ports=99", "ports=N"},
      {"udp:127.0.0.1:5000?classic=2", "classic=0|1"},
      {"udp:127.0.0.1:5000?ports=3&ports=4", "each key once"},
      {"udp:127.0.0.1:5000?ports=3&", "KEY=VALUE"},
      {"socketcan:vcan0?classic=1", "by its MTU"},
      {"loopback:a/b", "loopback name"},
      {"loopback?x=1", "classic=0 or classic=1"},
  };
  for (const auto& [url, why] : cases) {
    BusUrl u;
    std::string err;
    EXPECT_FALSE(parse_bus_url(url, &u, &err)) << url;
    EXPECT_NE(err.find(why), std::string::npos) << url << " -> " << err;
    EXPECT_NE(err.find("expected loopback"), std::string::npos) << "lists the valid forms";
    EXPECT_EQ(open_bus(url, &err), nullptr);
  }
}

TEST(BusUrl, OpenBusGivesWorkingEndpoints) {
  std::string err;
  auto a = open_bus("loopback:url-test", &err);
  auto b = open_bus("loopback:url-test", &err);
  ASSERT_TRUE(a && b) << err;
  CanFrame f;
  f.id = 0x42;
  f.len = 1;
  ASSERT_EQ(a->send(f, a->now_us() + 1000), CanStatus::kOk);
  EXPECT_EQ(b->receive(&f), CanStatus::kOk);
}
