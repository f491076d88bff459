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
  ThetaGenerator generator;
  generator.reset(5, 0.05f);
  ASSERT_EQ(archive->reset(2, generator), Status::kOk);
  float theta[kThetaDim];
  Fnv1a expected;
  for (int episode = 0; episode < 3; ++episode) {
    // Episode 0 random, 1 explores around 0, 2 exploits 1 (its θ again).
    const ThetaRecipe recipe =
        episode == 0 ? ThetaRecipe::random(0)
                     : (episode == 1 ? ThetaRecipe::explore(0, 0) : archive->recipe(1));
    if (episode == 0) generator.random_theta(0, theta);
    if (episode == 1) generator.add_noise(0, theta);
    const float outcome[2] = {static_cast<float>(episode), -0.5f * static_cast<float>(episode)};
    ASSERT_EQ(archive->append(recipe, outcome), Status::kOk);
    for (float t : theta) expected.add_float(t);
    for (float o : outcome) expected.add_float(o);
  }
  Fnv1a h;
  h.add_archive(*archive);
  EXPECT_EQ(h.h, expected.h);
  Fnv1a empty;
  ASSERT_EQ(archive->reset(2, generator), Status::kOk);
  empty.add_archive(*archive);
  EXPECT_EQ(empty.h, Fnv1a{}.h);
}

}  // namespace
}  // namespace curio::test
