// The test checksum is FNV-1a (32 bit) over little-endian bytes, and an archive's checksum
// is that of its θ and outcomes, episode by episode.
#include "firmware/explore/fnv1a.hpp"

#include <gtest/gtest.h>

#include <memory>

namespace curio::test {
namespace {

TEST(Fnv1a, MatchesTheReferenceOnBytes) {
  EXPECT_EQ(Fnv1a{}.h, 0x811c9dc5u);  // the offset basis: FNV-1a of no bytes
  Fnv1a abcd;
  abcd.add_u32(0x64636261u);  // "abcd", low byte first
  EXPECT_EQ(abcd.h, 0xce3479bdu);
  Fnv1a abcdefgh;
  abcdefgh.add_u64(0x6867666564636261u);
  EXPECT_EQ(abcdefgh.h, 0x76daaa8du);
  Fnv1a one;
  one.add_float(1.0f);  // bit pattern 0x3f800000
  EXPECT_EQ(one.h, 0x1b587698u);
}

TEST(Fnv1a, ArchiveIsThetaThenOutcomePerEpisode) {
  auto archive = std::make_unique<Archive>();
  ASSERT_EQ(archive->reset(2), Status::kOk);
  float theta[kThetaDim];
  Fnv1a expected;
  for (int episode = 0; episode < 3; ++episode) {
    for (int k = 0; k < kThetaDim; ++k) theta[k] = 0.01f * static_cast<float>(episode * 100 + k);
    const float outcome[2] = {static_cast<float>(episode), -0.5f * static_cast<float>(episode)};
    ASSERT_EQ(archive->append(theta, outcome), Status::kOk);
    for (float t : theta) expected.add_float(t);
    for (float o : outcome) expected.add_float(o);
  }
  Fnv1a h;
  h.add_archive(*archive);
  EXPECT_EQ(h.h, expected.h);
  Fnv1a empty;
  ASSERT_EQ(archive->reset(2), Status::kOk);
  empty.add_archive(*archive);
  EXPECT_EQ(empty.h, Fnv1a{}.h);
}

}  // namespace
}  // namespace curio::test
