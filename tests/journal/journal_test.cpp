// The journal (firmware/journal/journal.hpp) on the RAM-simulated flash: what is appended is
// what a scan after a restart finds; a torn or corrupt last record is dropped and reported;
// damage before the tail is an error naming the slot, and nothing is written after it.
#include "firmware/journal/journal.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "firmware/journal/crc32.hpp"
#include "tests/journal/journal_test_util.hpp"

namespace curio::journal::test {
namespace {

// 2 sectors of 4 KiB, 32-byte words: header block 128 B, slots of 64 B (4-dim outcome), 126 slots.
constexpr uint32_t kSector = 4096;
constexpr uint32_t kChip = 2 * kSector;
constexpr uint32_t kHeaderStride = 128;
constexpr uint32_t kStride = 64;

uint32_t slot_offset(uint32_t slot) {
  return kHeaderStride + slot * kStride;
}

struct Journal : ::testing::Test {
  FlashChip chip{kChip, kSector};
  std::unique_ptr<hal::SimFlash> flash = chip.flash();

  void write_journal(uint32_t n, uint32_t sync_every = 1) {
    JournalWriter w;
    ASSERT_EQ(w.create(flash.get(), test_identity(), sync_every), JournalStatus::kOk);
    for (uint32_t i = 0; i < n; ++i) ASSERT_EQ(w.append(entry(i)), JournalStatus::kOk) << i;
  }
  JournalScan reboot_and_scan() {
    flash = chip.flash();
    return scan_journal(*flash);
  }
};

TEST_F(Journal, GeometryGivesTheDocumentedStrides) {
  JournalWriter w;
  ASSERT_EQ(w.create(flash.get(), test_identity()), JournalStatus::kOk);
  EXPECT_EQ(w.header_stride(), kHeaderStride);
  EXPECT_EQ(w.record_stride(), kStride);
  EXPECT_EQ(w.slots(), (kChip - kHeaderStride) / kStride);
  EXPECT_EQ(slot_capacity(flash->geometry(), kDim), 126u);
}

TEST_F(Journal, AppendThenScanAfterRestartRoundTrips) {
  write_journal(100);
  const JournalScan scan = reboot_and_scan();
  ASSERT_EQ(scan.status, JournalStatus::kOk);
  EXPECT_FALSE(scan.torn_tail);
  EXPECT_EQ(scan.next_slot, 100u);
  EXPECT_EQ(first_difference(scan.header.identity, test_identity()), IdentityField::kNone);
  EXPECT_TRUE(holds_exactly(*flash, scan, 100));
}

TEST_F(Journal, EmptyJournalAndErasedStorage) {
  EXPECT_EQ(scan_journal(*flash).status, JournalStatus::kNoJournal);
  write_journal(0);
  const JournalScan scan = reboot_and_scan();
  EXPECT_TRUE(holds_exactly(*flash, scan, 0));
}

TEST_F(Journal, AppendOutOfOrderOrWrongDimensionIsRefused) {
  JournalWriter w;
  EXPECT_EQ(w.append(entry(0)), JournalStatus::kNotOpen);
  ASSERT_EQ(w.create(flash.get(), test_identity()), JournalStatus::kOk);
  EXPECT_EQ(w.append(entry(1)), JournalStatus::kWrongEpisode);
  EpisodeEntry e = entry(0);
  e.outcome_dim = kDim + 1;
  EXPECT_EQ(w.append(e), JournalStatus::kInvalidArgument);
  ASSERT_EQ(w.append(entry(0)), JournalStatus::kOk);
  EXPECT_EQ(w.append(entry(0)), JournalStatus::kWrongEpisode);
  EXPECT_TRUE(holds_exactly(*flash, reboot_and_scan(), 1));
}

TEST_F(Journal, FullStorageIsReportedNotWrapped) {
  write_journal(126);
  JournalWriter w;
  const JournalScan scan = reboot_and_scan();
  ASSERT_EQ(w.resume(flash.get(), scan), JournalStatus::kOk);
  EXPECT_EQ(w.append(entry(126)), JournalStatus::kFull);
  EXPECT_TRUE(holds_exactly(*flash, reboot_and_scan(), 126));
}

TEST_F(Journal, SyncEveryCountsStorageSyncs) {
  write_journal(125, 1);
  EXPECT_EQ(flash->counters().syncs, 1u + 125u);  // the header, then every record
  chip = FlashChip{kChip, kSector};
  flash = chip.flash();
  write_journal(125, 50);
  EXPECT_EQ(flash->counters().syncs, 1u + 2u);
  chip = FlashChip{kChip, kSector};
  flash = chip.flash();
  write_journal(125, 0);
  EXPECT_EQ(flash->counters().syncs, 1u);
}

TEST_F(Journal, CreateReplacesAnOldJournal) {
  write_journal(80);
  JournalWriter w;
  ASSERT_EQ(w.create(flash.get(), test_identity(8)), JournalStatus::kOk);
  for (uint32_t i = 0; i < 3; ++i) ASSERT_EQ(w.append(entry(i, 9)), JournalStatus::kOk);
  const JournalScan scan = reboot_and_scan();
  EXPECT_EQ(scan.header.identity.seed, 8u);
  EXPECT_TRUE(holds_exactly(*flash, scan, 3, [](uint32_t) { return 9u; }));
}

// A last record torn at any byte, or with any single bit flipped, is dropped and reported.
TEST_F(Journal, TornLastRecordIsDroppedAndReported) {
  write_journal(20);
  const std::vector<uint8_t> good = chip.memory;
  for (uint32_t cut = 1; cut < kStride; ++cut) {
    chip.memory = good;
    flash = chip.flash();
    // Pretend episode 20's slot was being programmed: its first `cut` bytes are new.
    JournalScan scan = scan_journal(*flash);
    JournalWriter w;
    ASSERT_EQ(w.resume(flash.get(), scan), JournalStatus::kOk);
    flash->power_cut_after(cut);
    EXPECT_EQ(w.append(entry(20)), JournalStatus::kStorageError);
    EXPECT_EQ(w.storage_status(), hal::StorageStatus::kPowerLost);
    scan = reboot_and_scan();
    ASSERT_EQ(scan.status, JournalStatus::kOk) << "cut " << cut;
    EXPECT_TRUE(scan.torn_tail);
    EXPECT_EQ(scan.torn_first, 20u);
    EXPECT_EQ(scan.torn_slots, 1u);
    EXPECT_EQ(scan.next_slot, 21u);
    EXPECT_TRUE(holds_exactly(*flash, scan, 20)) << "cut " << cut;
  }
}

TEST_F(Journal, CorruptLastRecordIsDroppedWithItsReason) {
  write_journal(20);
  const std::vector<uint8_t> good = chip.memory;
  for (uint32_t byte = 0; byte < 60; ++byte) {  // the record's 60 bytes (56 body + CRC)
    for (int bit = 0; bit < 8; bit += 3) {
      chip.memory = good;
      chip.memory[slot_offset(19) + byte] ^= static_cast<uint8_t>(1u << bit);
      const JournalScan scan = reboot_and_scan();
      ASSERT_EQ(scan.status, JournalStatus::kOk) << byte << ":" << bit;
      EXPECT_TRUE(scan.torn_tail);
      EXPECT_EQ(scan.torn_first, 19u);
      EXPECT_EQ(scan.torn_reason, byte < 4 ? DecodeResult::kBadMagic : DecodeResult::kBadCrc)
          << byte << ":" << bit << " " << to_string(scan.torn_reason);
      EXPECT_TRUE(holds_exactly(*flash, scan, 19));
    }
  }
}

TEST_F(Journal, NonZeroPaddingIsDamageToo) {
  write_journal(5);
  chip.memory[slot_offset(4) + 62] = 0x00 ^ 0x10;
  const JournalScan scan = reboot_and_scan();
  ASSERT_EQ(scan.status, JournalStatus::kOk);
  EXPECT_TRUE(scan.torn_tail);
  EXPECT_EQ(scan.torn_reason, DecodeResult::kBadLayout);
  EXPECT_EQ(scan.episodes, 4u);
}

// After a torn tail, resume acknowledges it with a skip record and appending goes on.
TEST_F(Journal, ResumeAfterTornTailWritesSkipAndContinues) {
  write_journal(20);
  chip.memory[slot_offset(19) + 45] ^= 0x04;
  JournalScan scan = reboot_and_scan();
  ASSERT_TRUE(scan.torn_tail);
  JournalWriter w;
  ASSERT_EQ(w.resume(flash.get(), scan), JournalStatus::kOk);
  EXPECT_EQ(w.counters().skips_written, 1u);
  EXPECT_EQ(w.episodes(), 19u);
  EXPECT_EQ(w.next_slot(), 21u);  // 19 torn, 20 the skip
  for (uint32_t i = 19; i < 30; ++i) ASSERT_EQ(w.append(entry(i, 1)), JournalStatus::kOk);
  scan = reboot_and_scan();
  ASSERT_EQ(scan.status, JournalStatus::kOk);
  EXPECT_FALSE(scan.torn_tail);
  EXPECT_EQ(scan.acknowledged_slots, 1u);
  EXPECT_TRUE(holds_exactly(*flash, scan, 30, [](uint32_t i) { return i >= 19 ? 1u : 0u; }));
}

// Damage before the tail: kCorrupt naming the first bad slot; the writer refuses to continue
// and the storage is left exactly as found.
TEST_F(Journal, CorruptionBeforeTheTailIsAnErrorAndNothingIsWritten) {
  for (uint32_t bad : {0u, 7u, 18u}) {
    chip = FlashChip{kChip, kSector};
    flash = chip.flash();
    write_journal(20);
    chip.memory[slot_offset(bad) + 41] ^= 0x80;
    const std::vector<uint8_t> damaged = chip.memory;
    const JournalScan scan = reboot_and_scan();
    EXPECT_EQ(scan.status, JournalStatus::kCorrupt) << bad;
    EXPECT_EQ(scan.bad_slot, bad);
    EXPECT_EQ(scan.bad_reason, DecodeResult::kBadCrc);
    EXPECT_EQ(scan.episodes, bad);  // the good records before it
    JournalWriter w;
    EXPECT_EQ(w.resume(flash.get(), scan), JournalStatus::kInvalidArgument);
    EXPECT_EQ(w.append(entry(20)), JournalStatus::kNotOpen);
    JournalReader r;
    EXPECT_EQ(r.open(flash.get(), scan), JournalStatus::kInvalidArgument);
    EXPECT_EQ(flash->counters().writes, 0u);
    EXPECT_EQ(flash->counters().erases, 0u);
    EXPECT_EQ(chip.memory, damaged);
  }
}

TEST_F(Journal, RecordsOutOfOrderOrMisplacedAreCorruption) {
  // Slot 5 holding a valid copy of slot 6 (right CRC, wrong slot number): not a torn tail.
  write_journal(10);
  for (uint32_t b = 0; b < kStride; ++b)
    chip.memory[slot_offset(5) + b] = chip.memory[slot_offset(6) + b];
  JournalScan scan = reboot_and_scan();
  EXPECT_EQ(scan.status, JournalStatus::kCorrupt);
  EXPECT_EQ(scan.bad_slot, 5u);
  EXPECT_EQ(scan.bad_reason, DecodeResult::kBadLayout);
}

TEST_F(Journal, BytesAfterTheEndAreCorruption) {
  // A stray programmed byte past the erased end: something wrote where the log never did.
  write_journal(10);
  chip.memory[slot_offset(40) + 3] = 0x00;
  const JournalScan scan = reboot_and_scan();
  EXPECT_EQ(scan.status, JournalStatus::kCorrupt);
  EXPECT_EQ(scan.bad_slot, 10u);
  EXPECT_EQ(scan.bad_reason, DecodeResult::kErased);
}

TEST_F(Journal, SkipRecordMustNameTheTornRun) {
  // Torn slot 19, then a skip naming slot 3: kCorrupt (a skip acknowledges only what it names).
  write_journal(20);
  chip.memory[slot_offset(19) + 45] ^= 0x04;
  JournalScan scan = reboot_and_scan();
  JournalWriter w;
  ASSERT_EQ(w.resume(flash.get(), scan), JournalStatus::kOk);
  // Rewrite the skip by hand: erase is per sector, so rebuild the chip image.
  std::vector<uint8_t> img = chip.memory;
  Record skip;
  skip.type = RecordType::kSkip;
  skip.slot = 20;
  skip.skipped_slot = 3;
  uint8_t buf[kMaxRecordBytes] = {};
  const size_t n = encode_record(skip, kDim, scan.header.crc, buf);
  for (uint32_t b = 0; b < kStride; ++b) img[slot_offset(20) + b] = b < n ? buf[b] : 0;
  chip.memory = img;
  scan = reboot_and_scan();
  EXPECT_EQ(scan.status, JournalStatus::kCorrupt);
  EXPECT_EQ(scan.bad_slot, 19u);
}

TEST_F(Journal, HeaderStates) {
  // Cut while the header was being written (rest erased): torn header, no episode.
  write_journal(0);
  chip.memory[50] ^= 0x01;
  EXPECT_EQ(reboot_and_scan().status, JournalStatus::kTornHeader);
  // A damaged header with records after it: corrupt, the records are not salvaged.
  chip = FlashChip{kChip, kSector};
  flash = chip.flash();
  write_journal(5);
  chip.memory[50] ^= 0x01;
  EXPECT_EQ(reboot_and_scan().status, JournalStatus::kCorruptHeader);
  // Another format version (with a valid CRC): refused as such.
  chip = FlashChip{kChip, kSector};
  flash = chip.flash();
  uint8_t h[kHeaderBytes];
  const size_t n = encode_header(test_identity(), kHeaderStride, kStride, 32, h);
  ASSERT_EQ(n, header_bytes(kVersionSpec));
  h[8] = 3;  // version 3
  const uint32_t crc = crc32(h, n - 4);
  for (int i = 0; i < 4; ++i) h[n - 4 + i] = static_cast<uint8_t>(crc >> (8 * i));
  for (size_t i = 0; i < n; ++i) chip.memory[i] = h[i];
  for (uint32_t i = static_cast<uint32_t>(n); i < kHeaderStride; ++i) chip.memory[i] = 0;
  EXPECT_EQ(reboot_and_scan().status, JournalStatus::kUnsupportedVersion);
}

TEST_F(Journal, AJournalFromAnotherGeometryIsNotMisread) {
  // Written with 32-byte words, read by a storage that says 16-byte words: the layout in the
  // header disagrees with the storage, so the scan refuses instead of misaligning slots.
  write_journal(5);
  FlashChip other{kChip, kSector, 16};
  other.memory = chip.memory;
  auto f = other.flash();
  EXPECT_EQ(scan_journal(*f).status, JournalStatus::kCorruptHeader);
}

TEST(JournalFormat, RecordOfAnotherRunNeverValidates) {
  // The header CRC (the run's nonce) is in every record's CRC.
  uint8_t buf[kMaxRecordBytes];
  Record r;
  r.entry = entry(3);
  r.slot = 3;
  const size_t n = encode_record(r, kDim, 0x11111111u, buf);
  ASSERT_EQ(n, record_bytes(kDim));
  Record back;
  EXPECT_EQ(decode_record(buf, n, kDim, 0x11111111u, &back), DecodeResult::kOk);
  EXPECT_TRUE(same_entry(back.entry, r.entry));
  EXPECT_EQ(decode_record(buf, n, kDim, 0x11111112u, &back), DecodeResult::kBadCrc);
  EXPECT_EQ(decode_record(buf, n, kDim + 1, 0x11111111u, &back), DecodeResult::kBadLayout);
}

TEST(JournalFormat, IdentityRoundTripsAndEveryFieldIsCompared) {
  const RunIdentity a = test_identity();
  uint8_t bytes[kIdentityBytes];
  encode_identity(a, bytes);
  RunIdentity b;
  decode_identity(bytes, &b);
  EXPECT_EQ(first_difference(a, b), IdentityField::kNone);
  struct Change {
    IdentityField field;
    void (*apply)(RunIdentity&);
  };
  const Change changes[] = {
      {IdentityField::kAlgorithmName, [](RunIdentity& x) { x.algorithm_name[0] = 'R'; }},
      {IdentityField::kAlgorithm, [](RunIdentity& x) { x.algorithm = 2; }},
      {IdentityField::kSeed, [](RunIdentity& x) { x.seed = 8; }},
      {IdentityField::kSigma, [](RunIdentity& x) { x.sigma = 0.1f; }},
      {IdentityField::kBootstrap, [](RunIdentity& x) { x.n_bootstrap = 51; }},
      {IdentityField::kEpisodes, [](RunIdentity& x) { x.n_episodes = 251; }},
      {IdentityField::kCompetenceCap, [](RunIdentity& x) { x.competence_cap = 0.25f; }},
      {IdentityField::kCompetenceMeasure, [](RunIdentity& x) { x.competence_measure = 1; }},
      {IdentityField::kWindow, [](RunIdentity& x) { x.window = 10.0f; }},
      {IdentityField::kEpsilon, [](RunIdentity& x) { x.epsilon = 0.2f; }},
      {IdentityField::kGoalBound, [](RunIdentity& x) { x.goal_bound = 2.0f; }},
      {IdentityField::kGoalKind, [](RunIdentity& x) { x.goal_kind = 1; }},
      {IdentityField::kOutcomeDim, [](RunIdentity& x) { x.outcome_dim = 5; }},
      {IdentityField::kModules, [](RunIdentity& x) { x.modules_hash ^= 1; }},
      {IdentityField::kModules, [](RunIdentity& x) { x.n_modules = 3; }},
      {IdentityField::kTieRule, [](RunIdentity& x) { x.tie_rule = 1; }},
      {IdentityField::kRequeryExploit, [](RunIdentity& x) { x.requery_exploit = 1; }},
      {IdentityField::kPhysics, [](RunIdentity& x) { x.physics = 1; }},
      {IdentityField::kWeights, [](RunIdentity& x) { x.weights_hash = 0xdeadbeef; }},
      {IdentityField::kEnvironment, [](RunIdentity& x) { x.environment_hash = 3; }},
      {IdentityField::kStrategy, [](RunIdentity& x) { x.frontier_share = 0.5f; }},
      {IdentityField::kStrategy, [](RunIdentity& x) { x.sigma_ladder[3] = 4.0f; }},
  };
  for (const Change& c : changes) {
    RunIdentity x = a;
    c.apply(x);
    EXPECT_EQ(first_difference(a, x), c.field) << to_string(c.field);
    // The change survives the header encoding (a journal records it).
    uint8_t h[kHeaderBytes];
    encode_header(x, kHeaderStride, kStride, 32, h);
    Header hd;
    ASSERT_EQ(decode_header(h, kHeaderBytes, &hd), DecodeResult::kOk) << to_string(c.field);
    EXPECT_EQ(first_difference(a, hd.identity), c.field);
  }
}

TEST(JournalFormat, SpecStrategyWritesVersionOneAnyOtherVersionTwo) {
  // SPEC's strategy: version 1, the 100 bytes every journal had before strategies were named.
  uint8_t h[kHeaderBytes];
  const RunIdentity spec = test_identity();
  ASSERT_FALSE(has_strategy(spec));
  EXPECT_EQ(encode_header(spec, kHeaderStride, kStride, 32, h), kHeaderBytesV1);
  EXPECT_EQ(h[8] | h[9] << 8, 1);
  Header hd;
  ASSERT_EQ(decode_header(h, kHeaderBytesV1, &hd), DecodeResult::kOk);
  EXPECT_EQ(first_difference(spec, hd.identity), IdentityField::kNone);
  // "beyond" (frontier goals in half the steps, σ ladder ×(1,2,2,4)): version 2, 120 bytes.
  RunIdentity beyond = spec;
  beyond.frontier_share = 0.5f;
  const float ladder[4] = {1.0f, 2.0f, 2.0f, 4.0f};
  for (int i = 0; i < 4; ++i) beyond.sigma_ladder[i] = ladder[i];
  EXPECT_EQ(encode_header(beyond, kHeaderStride, kStride, 32, h), kHeaderBytes);
  EXPECT_EQ(h[8] | h[9] << 8, 2);
  ASSERT_EQ(decode_header(h, kHeaderBytes, &hd), DecodeResult::kOk);
  EXPECT_EQ(first_difference(beyond, hd.identity), IdentityField::kNone);
  EXPECT_EQ(first_difference(spec, hd.identity), IdentityField::kStrategy);
  // A flipped strategy byte fails the CRC; a version 2 header naming SPEC's strategy (which
  // this format never writes) is a bad layout.
  h[100] ^= 0x01;
  EXPECT_EQ(decode_header(h, kHeaderBytes, &hd), DecodeResult::kBadCrc);
  encode_header(beyond, kHeaderStride, kStride, 32, h);
  for (int i = 96; i < 116; ++i) h[i] = 0;
  const uint32_t crc = crc32(h, kHeaderBytes - 4);
  for (int i = 0; i < 4; ++i) h[kHeaderBytes - 4 + i] = static_cast<uint8_t>(crc >> (8 * i));
  EXPECT_EQ(decode_header(h, kHeaderBytes, &hd), DecodeResult::kBadLayout);
}

TEST_F(Journal, AStrategyJournalRoundTripsOnFlashWithTheSameStrides) {
  RunIdentity beyond = test_identity();
  beyond.frontier_share = 0.5f;
  beyond.sigma_ladder[0] = 1.0f;
  JournalWriter w;
  ASSERT_EQ(w.create(flash.get(), beyond, 1), JournalStatus::kOk);
  EXPECT_EQ(w.header_stride(), kHeaderStride);  // 120 bytes still fit the 128-byte block
  for (uint32_t i = 0; i < 5; ++i) ASSERT_EQ(w.append(entry(i)), JournalStatus::kOk) << i;
  const JournalScan scan = reboot_and_scan();
  ASSERT_EQ(scan.status, JournalStatus::kOk);
  EXPECT_EQ(scan.episodes, 5u);
  EXPECT_EQ(scan.header.version, 2);
  EXPECT_EQ(first_difference(beyond, scan.header.identity), IdentityField::kNone);
}

}  // namespace
}  // namespace curio::journal::test
