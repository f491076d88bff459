// Power cuts on the simulated STM32H7 flash (128 KiB sectors), long-labelled: a cut after
// every byte of the erase of the sector holding the old journal's header and records (131,072
// cuts), each followed by a reboot, a scan and (every 16th cut) a full recovery; and every byte
// of the header write and of record writes across the whole first sector's slot boundaries.
#include <gtest/gtest.h>

#include "tests/journal/power_cut.hpp"

namespace curio::journal::test {
namespace {

constexpr uint32_t kSector = hal::SimFlash::kStm32h7SectorBytes;

TEST(PowerCutLong, EveryByteOfAnStm32h7SectorErase) {
  FlashChip chip(2 * kSector, kSector);
  // An old journal of 2500 records (160 KiB: into sector 1), replaced by a new run.
  const EraseSweep r = sweep_create_erase(chip, 2500, 0, kSector, 16);
  print("STM32H7 sector 0 (128 KiB)", r);
  EXPECT_EQ(r.cuts, kSector);
  EXPECT_EQ(r.old_journal_intact, 1u);
  EXPECT_EQ(r.corrupt_header, 99u);
  EXPECT_EQ(r.no_journal, kSector - 100);
}

TEST(PowerCutLong, EveryByteOfTheSecondSectorsErase) {
  FlashChip chip(2 * kSector, kSector);
  const EraseSweep r = sweep_create_erase(chip, 2500, kSector, 2 * kSector, 64);
  print("STM32H7 sector 1 (128 KiB)", r);
  EXPECT_EQ(r.no_journal, kSector);
}

TEST(PowerCutLong, EveryByteOfTheHeaderWriteStm32h7) {
  FlashChip chip(2 * kSector, kSector);
  sweep_header_write(chip);
}

TEST(PowerCutLong, EveryByteOfRecordWritesAcrossTheSectorBoundary) {
  FlashChip chip(2 * kSector, kSector);
  // 128 + k·64 = 131072 at k = 2046: the last slots of sector 0 and the first of sector 1.
  for (uint32_t k : {2044u, 2045u, 2046u, 2047u}) sweep_record_write(chip, k);
}

}  // namespace
}  // namespace curio::journal::test
