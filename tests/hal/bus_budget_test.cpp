// The bus budget (curio-can budget): worst-case frame lengths against the published bounds,
// and the frames of a period and an episode as the protocol's encoders make them.
#include <gtest/gtest.h>

#include "host_tools/can_tools/bus_budget.hpp"
#include "tests/hal/bus_test_util.hpp"

namespace curio::tools {
namespace {

using hal::test::frame_of;
using protocol::CanProfile;

TEST(BusBudget, ClassicFramesMatchTheWorstCaseBound) {
  // Davis et al. (2007): 135 bits for 8 bytes with an 11-bit id, 55 for none, 160 for 8 bytes
  // with a 29-bit id.
  EXPECT_EQ(worst_case_bits(frame_of(0x123, 8)).nominal, 135u);
  EXPECT_EQ(worst_case_bits(frame_of(0x123, 0)).nominal, 55u);
  EXPECT_EQ(worst_case_bits(frame_of(0x123, 8, false, true)).nominal, 160u);
  EXPECT_EQ(worst_case_bits(frame_of(0x123, 8)).data, 0u);
}

TEST(BusBudget, FdFramesSplitIntoNominalAndDataPhases) {
  // 64 bytes, 11-bit id: arbitration 17 + 4 stuff + 13 end bits at the nominal rate; ESI,
  // DLC and data 517 + 130 stuff + stuff count 4 + CRC 21 + 7 fixed stuff bits at the data
  // rate when it switches.
  hal::CanFrame f = frame_of(0x2A0, 64, true);  // FD with the bit-rate switch
  ASSERT_NE(f.flags & hal::kFlagBrs, 0);
  EXPECT_EQ(worst_case_bits(f).nominal, 34u);
  EXPECT_EQ(worst_case_bits(f).data, 679u);
  f.flags &= static_cast<uint8_t>(~hal::kFlagBrs);
  EXPECT_EQ(worst_case_bits(f).nominal, 713u);
  EXPECT_EQ(worst_case_bits(f).data, 0u);
  // Up to 16 bytes: CRC 17 with 6 fixed stuff bits.
  const hal::CanFrame g = frame_of(0x2A0, 16, true);
  EXPECT_EQ(worst_case_bits(g).nominal, 34u);
  EXPECT_EQ(worst_case_bits(g).data, 133u + 34u + 4u + 17u + 6u);
  // 2 Mbit/s data phase: the 64-byte frame takes 34 µs + 339.5 µs at 1M/2M.
  f.flags |= hal::kFlagBrs;
  EXPECT_NEAR(bus_seconds({f}, 1e6, 2e6), 34e-6 + 679 / 2e6, 1e-12);
}

TEST(BusBudget, AControlPeriodIsSevenTargetsASyncAndSevenAnswers) {
  const auto period = control_period_frames();
  ASSERT_EQ(period.size(), 15u);
  const TrafficBits t = traffic_bits(period);
  EXPECT_EQ(t.nominal_bits, 14u * 115u + 65u);  // 6-byte PDOs, a 1-byte SYNC
  // At 250 kbit/s that is 6.7 ms of the 10 ms period, at 125 kbit/s 13.4 ms: too long.
  EXPECT_NEAR(bus_seconds(period, 250e3, 250e3), 6.7e-3, 1e-9);
}

TEST(BusBudget, EpisodesCountTheProfilesFrames) {
  // 2 SDO + 50 × 15 + 40 heartbeats + capture request = 793, then the ground truth.
  EXPECT_EQ(episode_frames(CanProfile::kFd, false).size(), 793u + 1u);
  EXPECT_EQ(episode_frames(CanProfile::kClassic, false).size(), 793u + 5u);
  // The camera frame: FF + 195 CFs + one flow control (FD), FF + 1,756 CFs + FC (classic).
  EXPECT_EQ(episode_frames(CanProfile::kFd, true).size(), 794u + 197u);
  EXPECT_EQ(episode_frames(CanProfile::kClassic, true).size(), 798u + 1758u);
  // The classic profile never puts an FD frame on the bus.
  for (const hal::CanFrame& f : episode_frames(CanProfile::kClassic, true)) {
    EXPECT_FALSE(f.fd());
    EXPECT_LE(f.len, 8u);
  }
}

}  // namespace
}  // namespace curio::tools
