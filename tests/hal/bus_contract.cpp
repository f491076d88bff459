// The bus contract's tests; each test binary instantiates them for its backends.
#include "tests/hal/bus_contract.hpp"

namespace curio::hal::test {

TEST_P(BusContract, ClassicFrameReachesTheOtherEndpointNotTheSender) {
  const CanFrame f = frame_of(0x123, 8);
  ASSERT_EQ(a_->send(f, soon()), CanStatus::kOk);
  auto got = collect(*b_, 1);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_TRUE(same_frame(got[0], f));
  EXPECT_TRUE(collect(*a_, 1, 50'000).empty()) << "a sender does not hear its own frames";
  EXPECT_EQ(a_->stats().tx_frames, 1u);
  EXPECT_EQ(b_->stats().rx_frames, 1u);
  EXPECT_EQ(a_->state(), BusState::kErrorActive);
}

// A bus says whether it carries FD; a classic one refuses FD frames and counts them, and its
// classic frames still pass.
TEST_P(BusContract, CarriesFdAsTheBackendSaysAndAClassicBusRefusesFdFrames) {
  EXPECT_EQ(a_->carries_fd(), GetParam().fd);
  EXPECT_EQ(b_->carries_fd(), GetParam().fd);
  if (GetParam().fd) return;
  const CanFrame fd = frame_of(0x2A0, 48, true, false);
  EXPECT_EQ(a_->send(fd, soon()), CanStatus::kNotSupported);
  EXPECT_EQ(a_->stats().tx_rejected, 1u);
  const CanFrame classic = frame_of(0x2A1, 8);
  ASSERT_EQ(a_->send(classic, soon()), CanStatus::kOk);
  auto got = collect(*b_, 1);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_TRUE(same_frame(got[0], classic));
}

TEST_P(BusContract, EveryFdLengthAndIdWidthRoundTrips) {
  std::vector<CanFrame> sent;
  // A classic bus: every classic length instead.
  const uint8_t dlcs = GetParam().fd ? 16 : 9;
  for (uint8_t dlc = 0; dlc < dlcs; ++dlc) {
    sent.push_back(frame_of(0x18DAF120u, dlc_to_len(dlc), GetParam().fd, true, dlc));
    sent.push_back(frame_of(0x7FF, dlc_to_len(dlc), GetParam().fd, false, dlc));
  }
  sent.push_back(frame_of(0x1FFFFFFFu, 8, false, true));
  CanFrame remote = frame_of(0x321, 0);
  remote.flags |= kFlagRemote;
  remote.len = 4;  // a remote request carries a length but no data
  sent.push_back(remote);
  size_t accepted = 0;
  ASSERT_EQ(b_->send_batch(sent.data(), sent.size(), soon(), &accepted), CanStatus::kOk);
  EXPECT_EQ(accepted, sent.size());
  auto got = collect(*a_, sent.size());
  ASSERT_EQ(got.size(), sent.size());
  for (size_t i = 0; i < sent.size(); ++i) {
    if (sent[i].remote()) {
      EXPECT_EQ(got[i].id, sent[i].id);
      EXPECT_TRUE(got[i].remote());
      EXPECT_EQ(got[i].len, sent[i].len);
    } else {
      EXPECT_TRUE(same_frame(got[i], sent[i])) << "frame " << i;
    }
  }
}

TEST_P(BusContract, BatchKeepsOrderAndThirdEndpointHearsItToo) {
  std::string why;
  auto c = open_(&why);
  ASSERT_TRUE(c) << why;
  std::vector<CanFrame> sent;
  for (int i = 0; i < 300; ++i)
    sent.push_back(frame_of(0x200, GetParam().fd ? 64 : 8, GetParam().fd, false,
                            static_cast<uint8_t>(i)));
  for (size_t done = 0; done < sent.size();) {
    size_t k = 0;
    const CanStatus s = a_->send_batch(sent.data() + done, sent.size() - done, soon(), &k);
    ASSERT_TRUE(s == CanStatus::kOk || s == CanStatus::kWouldBlock) << to_string(s);
    done += k;
  }
  for (CanBus* rx : {b_.get(), c.get()}) {
    auto got = collect(*rx, sent.size());
    ASSERT_EQ(got.size(), sent.size());
    for (size_t i = 0; i < sent.size(); ++i) ASSERT_TRUE(same_frame(got[i], sent[i])) << i;
  }
}

TEST_P(BusContract, AcceptanceFiltersPassOnlyMatchingIds) {
  const CanFilter filters[] = {{0x120, 0x7F0, IdType::kStandard},
                               {0x18DAF120u, 0x1FFFFFFFu, IdType::kExtended}};
  ASSERT_EQ(b_->set_filters(filters, 2), CanStatus::kOk);
  const CanFrame frames[] = {frame_of(0x121, 1),                      // match
                             frame_of(0x131, 1),                      // no
                             frame_of(0x12F, 2),                      // match
                             frame_of(0x121, 1, false, true),         // extended: no
                             frame_of(0x18DAF120u, fd_len(), fd(), true),   // match
                             frame_of(0x18DAF121u, fd_len(), fd(), true)};  // no
  ASSERT_EQ(a_->send_batch(frames, 6, soon(), nullptr), CanStatus::kOk);
  auto got = collect(*b_, 3);
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[0].id, 0x121u);
  EXPECT_EQ(got[1].id, 0x12Fu);
  EXPECT_EQ(got[2].id, 0x18DAF120u);
  EXPECT_TRUE(collect(*b_, 1, 50'000).empty());

  CanFilter many[CanBus::kMaxFilters + 1] = {};
  EXPECT_EQ(b_->set_filters(many, CanBus::kMaxFilters + 1), CanStatus::kTooManyFilters);
  ASSERT_EQ(b_->set_filters(nullptr, 0), CanStatus::kOk);  // accept all again
  ASSERT_EQ(a_->send(frames[1], soon()), CanStatus::kOk);
  EXPECT_EQ(collect(*b_, 1).size(), 1u);
}

TEST_P(BusContract, ExpiredDeadlineDropsAndCounts) {
  const uint64_t now = a_->now_us();
  ASSERT_GT(now, 0u);
  EXPECT_EQ(a_->send(frame_of(0x100, 8), now - 1), CanStatus::kDeadlineExpired);
  EXPECT_EQ(a_->stats().tx_timedout, 1u);
  EXPECT_EQ(a_->stats().tx_frames, 0u);
  EXPECT_TRUE(collect(*b_, 1, 50'000).empty());
}

TEST_P(BusContract, InvalidFramesAreRefused) {
  CanFrame bad = frame_of(0x100, 8);
  bad.len = 9;  // classic frames carry at most 8 bytes
  EXPECT_EQ(a_->send(bad, soon()), CanStatus::kInvalidFrame);
  CanFrame bad_fd = frame_of(0x100, 12, true);
  bad_fd.len = 13;  // not an FD length
  EXPECT_EQ(a_->send(bad_fd, soon()), CanStatus::kInvalidFrame);
  CanFrame bad_id = frame_of(0x100, 1);
  bad_id.id = 0x800;  // does not fit 11 bits
  EXPECT_EQ(a_->send(bad_id, soon()), CanStatus::kInvalidFrame);
  EXPECT_EQ(a_->stats().tx_rejected, 3u);
  EXPECT_TRUE(collect(*b_, 1, 50'000).empty());
}

TEST_P(BusContract, WaitReadableTimesOutOnSilenceAndWakesOnAFrame) {
  EXPECT_EQ(b_->wait_readable(20'000), CanStatus::kTimeout);
  CanFrame f;
  EXPECT_EQ(b_->receive(&f), CanStatus::kEmpty);
  ASSERT_EQ(a_->send(frame_of(0x100, 1), soon()), CanStatus::kOk);
  EXPECT_EQ(b_->receive(&f, 1'000'000), CanStatus::kOk);
  EXPECT_EQ(f.id, 0x100u);
}

}  // namespace curio::hal::test
