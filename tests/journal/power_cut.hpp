// Power-cut sweeps on the simulated flash (hal/sim_flash.hpp cuts power after any number of
// byte changes): one record write, the skip record a resume writes, the header write and the
// sector erases of create(). After every cut the flash is "rebooted" (a new SimFlash over the
// same memory) and scanned: the journal must hold every completed record and nothing else,
// and appending must then go on correctly. Shared by the default suite (small sectors) and the
// long-labelled sweep (STM32H7 128 KiB sectors, every byte of a sector erase).
#pragma once
#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "tests/journal/journal_test_util.hpp"

namespace curio::journal::test {

inline constexpr uint32_t kOld = 0;  // salts: the journal before the cut, after recovery
inline constexpr uint32_t kNew = 1;

// A journal of `n` records (entry(i, kOld)) on a fresh chip.
inline void write_records(FlashChip& chip, uint32_t n, uint64_t seed = 7) {
  std::fill(chip.memory.begin(), chip.memory.end(), 0xFF);
  auto f = chip.flash();
  JournalWriter w;
  ASSERT_EQ(w.create(f.get(), test_identity(seed)), JournalStatus::kOk);
  for (uint32_t i = 0; i < n; ++i) ASSERT_EQ(w.append(entry(i, kOld)), JournalStatus::kOk);
}

// After recovery: resume (or create, if no journal is left), append 3 records, reboot, and the
// journal must be exactly `kept` old records then the 3 new ones.
inline ::testing::AssertionResult recovers(FlashChip& chip, uint32_t kept, uint64_t seed = 7) {
  auto f = chip.flash();
  JournalScan scan = scan_journal(*f);
  JournalWriter w;
  if (scan.status == JournalStatus::kOk) {
    if (w.resume(f.get(), scan) != JournalStatus::kOk)
      return ::testing::AssertionFailure() << "resume refused";
  } else if (w.create(f.get(), test_identity(seed)) != JournalStatus::kOk) {
    return ::testing::AssertionFailure() << "create refused";
  }
  for (uint32_t i = kept; i < kept + 3; ++i)
    if (const JournalStatus s = w.append(entry(i, kNew)); s != JournalStatus::kOk)
      return ::testing::AssertionFailure() << "append " << i << ": " << to_string(s);
  f = chip.flash();
  scan = scan_journal(*f);
  if (scan.status == JournalStatus::kOk && scan.header.identity.seed != seed)
    return ::testing::AssertionFailure() << "another run's header";
  return holds_exactly(*f, scan, kept + 3, [kept](uint32_t i) { return i < kept ? kOld : kNew; });
}

// Cut at every byte of the write of record `k` (cut = stride: the write completes).
inline void sweep_record_write(FlashChip& chip, uint32_t k) {
  write_records(chip, k);
  const std::vector<uint8_t> base = chip.memory;
  auto probe = chip.flash();
  JournalWriter pw;
  const JournalScan ps = scan_journal(*probe);
  ASSERT_EQ(pw.resume(probe.get(), ps), JournalStatus::kOk);
  const uint32_t stride = pw.record_stride();
  for (uint32_t cut = 0; cut <= stride; ++cut) {
    SCOPED_TRACE(::testing::Message() << "record " << k << ", cut after " << cut << " bytes");
    chip.memory = base;
    auto f = chip.flash();
    JournalWriter w;
    ASSERT_EQ(w.resume(f.get(), scan_journal(*f)), JournalStatus::kOk);
    f->power_cut_after(cut);
    const bool completed = w.append(entry(k, kOld)) == JournalStatus::kOk;
    ASSERT_EQ(completed, cut == stride);
    f = chip.flash();
    const JournalScan scan = scan_journal(*f);
    ASSERT_TRUE(holds_exactly(*f, scan, k + (completed ? 1 : 0)));
    EXPECT_EQ(scan.torn_tail, cut > 0 && !completed);
    if (scan.torn_tail) {
      EXPECT_EQ(scan.torn_first, k);
      EXPECT_EQ(scan.torn_slots, 1u);
    }
    ASSERT_TRUE(recovers(chip, k + (completed ? 1 : 0)));
  }
}

// Cut at every byte of the skip record that a resume writes after a torn tail; then a second
// cut-free recovery must acknowledge both torn slots.
inline void sweep_skip_write(FlashChip& chip, uint32_t k) {
  write_records(chip, k);
  {
    auto f = chip.flash();
    JournalWriter w;
    ASSERT_EQ(w.resume(f.get(), scan_journal(*f)), JournalStatus::kOk);
    f->power_cut_after(17);  // record k torn
    ASSERT_EQ(w.append(entry(k, kOld)), JournalStatus::kStorageError);
  }
  const std::vector<uint8_t> base = chip.memory;
  const uint32_t stride = [&] {
    auto f = chip.flash();
    JournalWriter w;
    EXPECT_EQ(w.resume(f.get(), scan_journal(*f)), JournalStatus::kOk);
    return w.record_stride();
  }();
  for (uint32_t cut = 0; cut <= stride; ++cut) {
    SCOPED_TRACE(::testing::Message() << "skip after record " << k << ", cut after " << cut);
    chip.memory = base;
    auto f = chip.flash();
    const JournalScan before = scan_journal(*f);
    ASSERT_TRUE(before.torn_tail);
    JournalWriter w;
    f->power_cut_after(cut);
    const bool completed = w.resume(f.get(), before) == JournalStatus::kOk;
    ASSERT_EQ(completed, cut == stride);
    f = chip.flash();
    const JournalScan scan = scan_journal(*f);
    ASSERT_TRUE(holds_exactly(*f, scan, k));
    if (completed) {
      EXPECT_FALSE(scan.torn_tail);
      EXPECT_EQ(scan.acknowledged_slots, 1u);
    } else {
      EXPECT_TRUE(scan.torn_tail);
      EXPECT_EQ(scan.torn_first, k);
      EXPECT_EQ(scan.torn_slots, cut == 0 ? 1u : 2u);  // the record, then the half skip
    }
    ASSERT_TRUE(recovers(chip, k));
  }
}

// Cut at every byte of the header write of create() on an erased chip.
inline void sweep_header_write(FlashChip& chip) {
  const uint32_t size = static_cast<uint32_t>(chip.memory.size());
  for (uint32_t cut = 0;; ++cut) {
    SCOPED_TRACE(::testing::Message() << "header, cut after " << cut << " bytes");
    std::fill(chip.memory.begin(), chip.memory.end(), 0xFF);
    auto f = chip.flash();
    JournalWriter w;
    f->power_cut_after(uint64_t{size} + cut);  // create() erases the whole chip first
    const bool completed = w.create(f.get(), test_identity()) == JournalStatus::kOk;
    f = chip.flash();
    const JournalScan scan = scan_journal(*f);
    if (completed) {
      EXPECT_EQ(cut, w.header_stride());
      ASSERT_TRUE(holds_exactly(*f, scan, 0));
      break;
    }
    if (cut == 0) {
      EXPECT_EQ(scan.status, JournalStatus::kNoJournal);
    } else if (cut < header_bytes(kVersionSpec)) {  // test_identity(): SPEC's strategy
      EXPECT_EQ(scan.status, JournalStatus::kTornHeader);
    } else {
      // The header's 100 bytes are in, only its zero padding is not: a valid, empty journal.
      EXPECT_TRUE(holds_exactly(*f, scan, 0));
    }
    ASSERT_TRUE(recovers(chip, 0));
  }
}

// What a cut during create()'s erases leaves, by scan status.
struct EraseSweep {
  uint32_t cuts = 0;
  uint32_t old_journal_intact = 0;  // cut before the first byte changed
  uint32_t no_journal = 0;
  uint32_t corrupt_header = 0;
  uint32_t torn_header = 0;
};

// create() of a new run (seed 8) over an old journal of `n` records (seed 7), cut after each
// of the bytes [from, to) of its erases (byte b of the chip is erased by the b+1-th change).
// The old run's records must never be readable as a journal again once the erase has begun,
// and the new journal must take its place whatever the cut.
inline EraseSweep sweep_create_erase(FlashChip& chip, uint32_t n, uint32_t from, uint32_t to,
                                     uint32_t verify_every = 1) {
  EraseSweep r;
  write_records(chip, n, 7);
  const std::vector<uint8_t> base = chip.memory;
  for (uint32_t cut = from; cut < to; ++cut) {
    SCOPED_TRACE(::testing::Message() << "erase, cut after " << cut << " bytes");
    std::copy(base.begin(), base.end(), chip.memory.begin());
    auto f = chip.flash();
    JournalWriter w;
    f->power_cut_after(cut);
    EXPECT_EQ(w.create(f.get(), test_identity(8)), JournalStatus::kStorageError);
    f = chip.flash();
    const JournalScan scan = scan_journal(*f);
    ++r.cuts;
    if (cut == 0) {
      EXPECT_EQ(scan.status, JournalStatus::kOk);
      EXPECT_EQ(scan.header.identity.seed, 7u);
      EXPECT_TRUE(holds_exactly(*f, scan, n));
      ++r.old_journal_intact;
      continue;
    }
    switch (scan.status) {
      case JournalStatus::kNoJournal:
        ++r.no_journal;
        break;
      case JournalStatus::kCorruptHeader:
        ++r.corrupt_header;
        break;
      case JournalStatus::kTornHeader:
        ++r.torn_header;
        break;
      default:
        ADD_FAILURE() << "scan " << to_string(scan.status) << " after the erase began";
        return r;
    }
    // Recovery as a new run: create again (what --replace or a fresh start does).
    if ((cut - from) % verify_every == 0 && !recovers(chip, 0, 8)) {
      ADD_FAILURE() << "no recovery after cut " << cut;
      return r;
    }
  }
  return r;
}

inline void print(const char* what, const EraseSweep& r) {
  std::printf(
      "%s: %u cuts: old journal intact %u, no journal %u, corrupt header %u, torn header %u\n",
      what, r.cuts, r.old_journal_intact, r.no_journal, r.corrupt_header, r.torn_header);
}

}  // namespace curio::journal::test
