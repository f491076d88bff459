// Shared pieces of the journal tests: a RAM flash that survives "power cycles" (the memory
// outlives each SimFlash), a run identity, episode entries with distinct, checkable content.
#pragma once
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include "firmware/journal/journal.hpp"
#include "hal/sim_flash.hpp"

namespace curio::journal::test {

inline constexpr int kDim = 4;  // engineered features: [distractor x, y, ball x, y]

inline RunIdentity test_identity(uint64_t seed = 7) {
  RunIdentity id;
  id.seed = seed;
  id.n_bootstrap = 50;
  id.n_episodes = 250;
  id.sigma = 0.05f;
  id.competence_cap = 0.5f;
  id.window = 20.0f;
  id.epsilon = 0.1f;
  id.goal_bound = 1.0f;
  id.algorithm = 1;
  id.outcome_dim = kDim;
  id.n_modules = 2;
  id.physics = 0;
  id.modules_hash = 0x1234abcdu;
  std::strncpy(id.algorithm_name, "MGE-EFR", kAlgorithmNameBytes - 1);
  return id;
}

// Entry `i` with every field a function of i (so a mix-up of records shows).
inline EpisodeEntry entry(uint32_t i, uint32_t salt = 0) {
  EpisodeEntry e;
  e.episode = i;
  e.kind = static_cast<uint8_t>(i % 3);
  e.module = static_cast<int8_t>(static_cast<int>(i % 4) - 1);
  e.exploit = i % 5 == 0;
  e.grasped = i % 7 == 0;
  e.attempts = static_cast<uint8_t>(1 + i % 3);
  e.outcome_dim = kDim;
  const float f = static_cast<float>(i) + 0.001f * static_cast<float>(salt);
  e.ball[0] = 0.5f + f;
  e.ball[1] = -0.25f * f;
  e.distractor[0] = 0.125f * f;
  e.distractor[1] = -f;
  e.progress = 1.0f / (1.0f + f);
  for (int d = 0; d < kDim; ++d) e.outcome[d] = f * static_cast<float>(d + 1) - 3.0f;
  return e;
}

inline bool same_entry(const EpisodeEntry& a, const EpisodeEntry& b) {
  return a.episode == b.episode && a.kind == b.kind && a.module == b.module &&
         a.exploit == b.exploit && a.grasped == b.grasped && a.attempts == b.attempts &&
         a.outcome_dim == b.outcome_dim && std::memcmp(a.ball, b.ball, sizeof a.ball) == 0 &&
         std::memcmp(a.distractor, b.distractor, sizeof a.distractor) == 0 &&
         std::memcmp(&a.progress, &b.progress, 4) == 0 &&
         std::memcmp(a.outcome, b.outcome, sizeof(float) * a.outcome_dim) == 0;
}

// A flash array that outlives power cycles; flash() is a fresh SimFlash over it (a reboot).
struct FlashChip {
  FlashChip(uint32_t size, uint32_t sector, uint32_t word = hal::SimFlash::kStm32h7WordBytes)
      : memory(size, 0xFF), sector_bytes(sector), word_bytes(word) {}
  std::unique_ptr<hal::SimFlash> flash() {
    return std::make_unique<hal::SimFlash>(memory.data(), static_cast<uint32_t>(memory.size()),
                                           sector_bytes, word_bytes);
  }
  std::vector<uint8_t> memory;
  uint32_t sector_bytes;
  uint32_t word_bytes;
};

// Every episode entry the reader yields after a kOk scan.
inline std::vector<EpisodeEntry> read_all(hal::Storage& s, const JournalScan& scan) {
  std::vector<EpisodeEntry> out;
  JournalReader r;
  EXPECT_EQ(r.open(&s, scan), JournalStatus::kOk);
  for (;;) {
    EpisodeEntry e;
    bool end = false;
    const JournalStatus st = r.next(&e, &end);
    EXPECT_EQ(st, JournalStatus::kOk);
    if (st != JournalStatus::kOk || end) break;
    out.push_back(e);
  }
  return out;
}

// The reader yields exactly entries 0..n-1 (entry(i, salt_of(i))).
template <typename Salt>
::testing::AssertionResult holds_exactly(hal::Storage& s, const JournalScan& scan, uint32_t n,
                                         Salt salt_of) {
  if (scan.status != JournalStatus::kOk)
    return ::testing::AssertionFailure() << "scan " << to_string(scan.status);
  if (scan.episodes != n)
    return ::testing::AssertionFailure() << "scan has " << scan.episodes << " episodes, want " << n;
  const std::vector<EpisodeEntry> got = read_all(s, scan);
  if (got.size() != n)
    return ::testing::AssertionFailure() << "reader gave " << got.size() << ", want " << n;
  for (uint32_t i = 0; i < n; ++i)
    if (!same_entry(got[i], entry(i, salt_of(i))))
      return ::testing::AssertionFailure() << "episode " << i << " differs";
  return ::testing::AssertionSuccess();
}
inline ::testing::AssertionResult holds_exactly(hal::Storage& s, const JournalScan& scan,
                                                uint32_t n) {
  return holds_exactly(s, scan, n, [](uint32_t) { return 0u; });
}

}  // namespace curio::journal::test
