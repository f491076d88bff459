// Power cuts on the simulated flash, default-suite sizes: every byte of a record write (first
// slot, mid-sector, first slot of the second sector; 4 KiB sectors and the STM32H7's 128 KiB),
// of a resume's skip record, of the header write, and of every byte of create()'s sector
// erases on a 2 × 4 KiB chip. tests/journal/power_cut_long_test.cpp sweeps a whole 128 KiB
// sector erase.
#include <gtest/gtest.h>

#include "tests/journal/power_cut.hpp"

namespace curio::journal::test {
namespace {

constexpr uint32_t kSmallSector = 4096;
// Header 128 B, then 64-byte slots: slot 62 is the first of sector 1 (128 + 62·64 = 4096).
constexpr uint32_t kFirstSlotOfSector1 = 62;

TEST(PowerCut, EveryByteOfARecordWriteSmallSectors) {
  FlashChip chip(2 * kSmallSector, kSmallSector);
  for (uint32_t k : {0u, 5u, kFirstSlotOfSector1 - 1, kFirstSlotOfSector1})
    sweep_record_write(chip, k);
}

TEST(PowerCut, EveryByteOfARecordWriteStm32h7Sectors) {
  FlashChip chip(2 * hal::SimFlash::kStm32h7SectorBytes, hal::SimFlash::kStm32h7SectorBytes);
  for (uint32_t k : {0u, 40u}) sweep_record_write(chip, k);
}

TEST(PowerCut, EveryByteOfTheSkipRecordWrite) {
  FlashChip chip(2 * kSmallSector, kSmallSector);
  for (uint32_t k : {0u, 9u, kFirstSlotOfSector1 - 1}) sweep_skip_write(chip, k);
}

TEST(PowerCut, EveryByteOfTheHeaderWrite) {
  FlashChip chip(2 * kSmallSector, kSmallSector);
  sweep_header_write(chip);
}

TEST(PowerCut, EveryByteOfCreatesSectorErasesSmallSectors) {
  FlashChip chip(2 * kSmallSector, kSmallSector);
  // An old journal reaching into sector 1, replaced by a new run; a cut after every one of the
  // 8192 erased bytes.
  const EraseSweep r = sweep_create_erase(chip, 100, 0, 2 * kSmallSector);
  print("2 x 4 KiB sectors", r);
  EXPECT_EQ(r.cuts, 2 * kSmallSector);
  EXPECT_EQ(r.old_journal_intact, 1u);
  // The header's bytes 0..99 only partly erased, records after it in sector 0: corrupt header
  // (refused by --resume, replaced by --replace); once all 100 header bytes read erased: none.
  EXPECT_EQ(r.corrupt_header, 99u);
  EXPECT_EQ(r.no_journal, 2 * kSmallSector - 100);
}

}  // namespace
}  // namespace curio::journal::test
