// Resume by replay (firmware/journal/replay.hpp) against the kinematic arm in-process: a run
// journaled on the simulated STM32H7 flash, replayed into a fresh Explorer without the arm,
// ends with the archive checksum of curio-lab's uninterrupted run with the same seed; so does
// a run "killed" part way, replayed, and continued.
#include "firmware/journal/replay.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "tests/journal/kinematic_run.hpp"

namespace curio::journal::test {
namespace {

struct CountingObserver final : ReplayObserver {
  void on_replayed(const EpisodeEntry& e, const Explorer& x) override {
    EXPECT_EQ(static_cast<int>(e.episode) + 1, x.episode());
    ++n;
  }
  int n = 0;
};

class Replay : public ::testing::TestWithParam<const char*> {};

TEST_P(Replay, ReplayedExplorerHasTheLiveRunsArchive) {
  const lab::RunSpec spec = spec_of(GetParam(), 11);
  const uint32_t live = live_checksum(spec);
  // STM32H7 geometry: 2 sectors of 128 KiB, 32-byte flash words.
  FlashChip chip(2 * hal::SimFlash::kStm32h7SectorBytes, hal::SimFlash::kStm32h7SectorBytes);
  {
    auto flash = chip.flash();
    JournalWriter w;
    ASSERT_EQ(w.create(flash.get(), identity(spec)), JournalStatus::kOk);
    ArmRun run(spec);
    run.run_until(1 << 30, &w);
    ASSERT_EQ(checksum(*run.explorer), live) << "the test's own loop is curio-lab's run";
  }
  auto flash = chip.flash();  // a restart: only the flash is left
  const JournalScan scan = scan_journal(*flash);
  ASSERT_EQ(scan.status, JournalStatus::kOk);
  ASSERT_EQ(scan.episodes, static_cast<uint32_t>(kBootstrap + kEpisodes));
  JournalReader reader;
  ASSERT_EQ(reader.open(flash.get(), scan), JournalStatus::kOk);
  ArmRun fresh(spec);  // its world is never used
  CountingObserver obs;
  ReplayReport rep;
  ASSERT_EQ(replay_journal(reader, *fresh.explorer, &obs, &rep), JournalStatus::kOk) << rep.what;
  EXPECT_EQ(rep.episodes, static_cast<uint32_t>(kBootstrap + kEpisodes));
  EXPECT_EQ(obs.n, kBootstrap + kEpisodes);
  EXPECT_TRUE(fresh.explorer->done());
  EXPECT_EQ(checksum(*fresh.explorer), live);
}

// Killed at several points (the journal as a power cut leaves it), resumed by replay, the arm
// positioned at the next episode (reset_to_episode, as curio-sim serve does), run to the end.
TEST_P(Replay, KilledReplayedAndContinuedEqualsTheLiveRun) {
  const lab::RunSpec spec = spec_of(GetParam(), 12);
  const uint32_t live = live_checksum(spec);
  FlashChip chip(2 * hal::SimFlash::kStm32h7SectorBytes, hal::SimFlash::kStm32h7SectorBytes);
  {
    auto flash = chip.flash();
    JournalWriter w;
    ASSERT_EQ(w.create(flash.get(), identity(spec)), JournalStatus::kOk);
    ArmRun run(spec);
    run.run_until(37, &w);  // inside the bootstrap
  }
  for (int kill_at : {120, 121, 299}) {
    auto flash = chip.flash();
    const JournalScan scan = scan_journal(*flash);
    ASSERT_EQ(scan.status, JournalStatus::kOk);
    ArmRun run(spec);
    JournalReader reader;
    ASSERT_EQ(reader.open(flash.get(), scan), JournalStatus::kOk);
    ASSERT_EQ(replay_journal(reader, *run.explorer, nullptr, nullptr), JournalStatus::kOk);
    ASSERT_EQ(run.explorer->episode(), static_cast<int>(scan.episodes));
    JournalWriter w;
    ASSERT_EQ(w.resume(flash.get(), scan), JournalStatus::kOk);
    run.world->reset_to_episode(scan.episodes);
    run.run_until(kill_at, &w);
    if (kill_at == 121) {
      // This time the power goes while episode 121's record is half written.
      flash->power_cut_after(20);
      EpisodeEntry torn = entry(121);
      EXPECT_EQ(w.append(torn), JournalStatus::kStorageError);
    }
  }
  auto flash = chip.flash();
  const JournalScan scan = scan_journal(*flash);
  ASSERT_EQ(scan.episodes, 299u);
  EXPECT_EQ(scan.acknowledged_slots, 1u);  // the torn slot of the cut at 121
  ArmRun run(spec);
  JournalReader reader;
  ASSERT_EQ(reader.open(flash.get(), scan), JournalStatus::kOk);
  ASSERT_EQ(replay_journal(reader, *run.explorer, nullptr, nullptr), JournalStatus::kOk);
  JournalWriter w;
  ASSERT_EQ(w.resume(flash.get(), scan), JournalStatus::kOk);
  run.world->reset_to_episode(scan.episodes);
  run.run_until(1 << 30, &w);
  EXPECT_EQ(checksum(*run.explorer), live);
  // And the whole journal replays to the same state again.
  auto again = chip.flash();
  const JournalScan full = scan_journal(*again);
  ASSERT_EQ(full.episodes, 300u);
  ArmRun check(spec);
  ASSERT_EQ(reader.open(again.get(), full), JournalStatus::kOk);
  ASSERT_EQ(replay_journal(reader, *check.explorer, nullptr, nullptr), JournalStatus::kOk);
  EXPECT_EQ(checksum(*check.explorer), live);
}

INSTANTIATE_TEST_SUITE_P(Algorithms, Replay, ::testing::Values("MGE-EFR", "RGE-EFR"),
                         [](const auto& info) {
                           std::string n = info.param;
                           for (char& c : n)
                             if (c == '-') c = '_';
                           return n;
                         });

// A journal that is not this explorer's run: replay stops at the first record the explorer
// disagrees with, names it, and the explorer is not silently given another run's outcomes.
TEST(ReplayMismatch, AnotherSeedsJournalIsCaught) {
  const lab::RunSpec spec = spec_of("MGE-EFR", 11);
  FlashChip chip(2 * 4096 * 8, 4096 * 8);
  auto flash = chip.flash();
  JournalWriter w;
  ASSERT_EQ(w.create(flash.get(), identity(spec)), JournalStatus::kOk);
  ArmRun run(spec);
  run.run_until(300, &w);
  const JournalScan scan = scan_journal(*flash);
  ASSERT_EQ(scan.status, JournalStatus::kOk);
  ArmRun other(spec_of("MGE-EFR", 12));
  JournalReader reader;
  ASSERT_EQ(reader.open(flash.get(), scan), JournalStatus::kOk);
  ReplayReport rep;
  EXPECT_EQ(replay_journal(reader, *other.explorer, nullptr, &rep), JournalStatus::kReplayMismatch);
  EXPECT_GE(rep.episode, static_cast<uint32_t>(kBootstrap));  // the bootstrap cannot tell
  EXPECT_STRNE(rep.what, "");
}

TEST(ReplayMismatch, AWrongKindIsNamedWithItsEpisode) {
  const lab::RunSpec spec = spec_of("MGE-EFR", 11);
  FlashChip chip(2 * 4096 * 8, 4096 * 8);
  auto flash = chip.flash();
  JournalWriter w;
  ASSERT_EQ(w.create(flash.get(), identity(spec)), JournalStatus::kOk);
  ArmRun run(spec);
  run.run_until(60, &w);
  // Episode 60 journaled with the wrong kind (a build whose explorer behaves differently).
  float theta[kThetaDim];
  ASSERT_EQ(run.explorer->propose(theta), Status::kOk);
  EpisodeEntry e;
  e.episode = 60;
  e.kind = static_cast<uint8_t>(EpisodeKind::kBootstrap);
  e.module = static_cast<int8_t>(run.explorer->module());
  e.outcome_dim = 4;
  ASSERT_EQ(w.append(e), JournalStatus::kOk);
  const JournalScan scan = scan_journal(*flash);
  ArmRun fresh(spec);
  JournalReader reader;
  ASSERT_EQ(reader.open(flash.get(), scan), JournalStatus::kOk);
  ReplayReport rep;
  EXPECT_EQ(replay_journal(reader, *fresh.explorer, nullptr, &rep), JournalStatus::kReplayMismatch);
  EXPECT_EQ(rep.episode, 60u);
  EXPECT_EQ(rep.episodes, 60u);
  EXPECT_STREQ(rep.what, "episode kind");
}

}  // namespace
}  // namespace curio::journal::test
