#include "tests/explore/explore_smoke.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>

namespace curio::test {
namespace {

// The same run as the Cortex-M7 QEMU test (tests/explore/qemu/explore_smoke_main.cpp).
TEST(ExploreSmoke, HostChecksumMatchesTheCortexM7Golden) {
  auto explorer = std::make_unique<Explorer>();
  const SmokeResult r = run_smoke(*explorer);
  ASSERT_EQ(r.status, Status::kOk);
  EXPECT_EQ(r.episodes, kSmokeBootstrap + kSmokeEpisodes);
  EXPECT_GT(r.nn_queries, 100u);
  std::printf("explore smoke checksum 0x%08x\n", static_cast<unsigned>(r.checksum));
  EXPECT_EQ(r.checksum, kSmokeChecksum) << "update kSmokeChecksum only for a deliberate change";
}

TEST(ExploreSmoke, FullSizeRunChecksumMatchesTheCortexM7Golden) {
  auto explorer = std::make_unique<Explorer>();
  const SmokeResult r = run_smoke(*explorer, kFullBootstrap, kFullEpisodes);
  ASSERT_EQ(r.status, Status::kOk);
  EXPECT_EQ(r.episodes, kFullBootstrap + kFullEpisodes);
  std::printf("explore full-size checksum 0x%08x\n", static_cast<unsigned>(r.checksum));
  EXPECT_EQ(r.checksum, kFullChecksum) << "update kFullChecksum only for a deliberate change";
}

}  // namespace
}  // namespace curio::test
