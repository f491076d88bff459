// The storage contract (hal/storage.hpp), run against every backend: the RAM-simulated NOR
// flash (small sectors, and the STM32H7's 128 KiB ones) and the POSIX file. The journal
// relies on exactly these behaviours, so it works the same on a file as on flash.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "hal/host/posix_file_storage.hpp"
#include "hal/sim_flash.hpp"
#include "hal/storage.hpp"

namespace curio::hal {
namespace {

struct StorageBackend {
  std::string name;
  // Opens the backend's storage; `fresh`: a new, erased one; otherwise the same one again
  // (as after a restart).
  std::function<std::unique_ptr<Storage>(bool fresh)> open;
};

void PrintTo(const StorageBackend& b, std::ostream* os) { *os << b.name; }

StorageBackend sim_backend(std::string name, uint32_t size, uint32_t sector) {
  auto memory = std::make_shared<std::vector<uint8_t>>(size, 0xFF);
  return {name, [memory, size, sector](bool fresh) -> std::unique_ptr<Storage> {
            if (fresh) std::fill(memory->begin(), memory->end(), 0xFF);
            return std::make_unique<SimFlash>(memory->data(), size, sector);
          }};
}

StorageBackend file_backend() {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("curio_storage_contract_" + std::to_string(::getpid()) + ".bin"))
                               .string();
  return {"posix_file", [path](bool fresh) -> std::unique_ptr<Storage> {
            if (fresh) std::filesystem::remove(path);
            std::string why;
            auto s = PosixFileStorage::open(path, &why, {64 * 1024, 4096, 32, 0xFF});
            EXPECT_TRUE(s) << why;
            return s;
          }};
}

class StorageContract : public ::testing::TestWithParam<StorageBackend> {
 protected:
  void SetUp() override {
    s_ = GetParam().open(true);
    ASSERT_TRUE(s_);
    g_ = s_->geometry();
  }
  std::vector<uint8_t> read(uint32_t at, uint32_t n) {
    std::vector<uint8_t> v(n);
    EXPECT_EQ(s_->read(at, v.data(), n), StorageStatus::kOk);
    return v;
  }
  std::vector<uint8_t> pattern(uint32_t n, uint8_t seed) {
    std::vector<uint8_t> v(n);
    for (uint32_t i = 0; i < n; ++i) v[i] = static_cast<uint8_t>(seed + 7 * i);
    return v;
  }
  std::unique_ptr<Storage> s_;
  StorageGeometry g_;
};

TEST_P(StorageContract, GeometryIsConsistent) {
  EXPECT_GT(g_.size_bytes, 0u);
  EXPECT_EQ(g_.size_bytes % g_.sector_bytes, 0u);
  EXPECT_EQ(g_.sector_bytes % g_.write_block_bytes, 0u);
  EXPECT_EQ(g_.erased_value, 0xFF);
  EXPECT_GE(g_.size_bytes / g_.sector_bytes, 2u) << "tests need two sectors";
}

TEST_P(StorageContract, FreshStorageReadsErasedEverywhere) {
  for (uint32_t at : {0u, g_.sector_bytes - 8, g_.size_bytes - 8}) {
    for (uint8_t b : read(at, 8)) ASSERT_EQ(b, 0xFF) << at;
  }
}

TEST_P(StorageContract, WrittenBlocksReadBackAndSurviveAReopen) {
  const uint32_t w = g_.write_block_bytes;
  const auto a = pattern(3 * w, 1);
  const auto b = pattern(w, 99);
  ASSERT_EQ(s_->write(0, a.data(), 3 * w), StorageStatus::kOk);
  ASSERT_EQ(s_->write(g_.sector_bytes + w, b.data(), w), StorageStatus::kOk);
  ASSERT_EQ(s_->sync(), StorageStatus::kOk);
  EXPECT_EQ(read(0, 3 * w), a);
  EXPECT_EQ(read(g_.sector_bytes + w, w), b);
  for (uint8_t x : read(3 * w, w)) EXPECT_EQ(x, 0xFF);
  // Unaligned reads are fine.
  EXPECT_EQ(read(1, 5), std::vector<uint8_t>(a.begin() + 1, a.begin() + 6));
  s_.reset();
  s_ = GetParam().open(false);
  EXPECT_EQ(read(0, 3 * w), a);
  EXPECT_EQ(read(g_.sector_bytes + w, w), b);
}

TEST_P(StorageContract, AWriteBlockIsProgrammedOnceUntilErased) {
  const uint32_t w = g_.write_block_bytes;
  const auto a = pattern(w, 3);
  const auto b = pattern(2 * w, 50);
  ASSERT_EQ(s_->write(w, a.data(), w), StorageStatus::kOk);
  // Overlapping a programmed block: refused, and nothing of the call is written.
  EXPECT_EQ(s_->write(0, b.data(), 2 * w), StorageStatus::kNotErased);
  for (uint8_t x : read(0, w)) EXPECT_EQ(x, 0xFF);
  EXPECT_EQ(read(w, w), a);
  EXPECT_EQ(s_->write(w, b.data(), w), StorageStatus::kNotErased);
  EXPECT_EQ(read(w, w), a);
  ASSERT_EQ(s_->erase(0, g_.sector_bytes), StorageStatus::kOk);
  for (uint8_t x : read(0, 2 * w)) EXPECT_EQ(x, 0xFF);
  EXPECT_EQ(s_->write(0, b.data(), 2 * w), StorageStatus::kOk);
  EXPECT_EQ(read(0, 2 * w), b);
  EXPECT_GE(s_->counters().errors, 2u);
}

TEST_P(StorageContract, EraseTouchesOnlyItsSectors) {
  const uint32_t w = g_.write_block_bytes;
  const auto a = pattern(w, 10);
  const auto b = pattern(w, 20);
  ASSERT_EQ(s_->write(g_.sector_bytes - w, a.data(), w), StorageStatus::kOk);
  ASSERT_EQ(s_->write(g_.sector_bytes, b.data(), w), StorageStatus::kOk);
  ASSERT_EQ(s_->erase(g_.sector_bytes, g_.sector_bytes), StorageStatus::kOk);
  EXPECT_EQ(read(g_.sector_bytes - w, w), a);
  for (uint8_t x : read(g_.sector_bytes, w)) EXPECT_EQ(x, 0xFF);
  // Erasing the last sectors and writing there again works (file: truncated, then extended).
  ASSERT_EQ(s_->erase(0, g_.size_bytes), StorageStatus::kOk);
  for (uint8_t x : read(g_.sector_bytes - w, w)) EXPECT_EQ(x, 0xFF);
  ASSERT_EQ(s_->write(g_.size_bytes - w, b.data(), w), StorageStatus::kOk);
  EXPECT_EQ(read(g_.size_bytes - w, w), b);
}

TEST_P(StorageContract, MisalignedAndOutOfRangeCallsAreRefusedAndChangeNothing) {
  const uint32_t w = g_.write_block_bytes;
  const auto a = pattern(2 * w, 5);
  ASSERT_EQ(s_->write(0, a.data(), w), StorageStatus::kOk);
  EXPECT_EQ(s_->write(1, a.data(), w), StorageStatus::kMisaligned);
  EXPECT_EQ(s_->write(w, a.data(), w - 1), StorageStatus::kMisaligned);
  EXPECT_EQ(s_->write(g_.size_bytes - w, a.data(), 2 * w), StorageStatus::kOutOfRange);
  EXPECT_EQ(s_->write(g_.size_bytes, a.data(), w), StorageStatus::kOutOfRange);
  EXPECT_EQ(s_->erase(w, g_.sector_bytes), StorageStatus::kMisaligned);
  EXPECT_EQ(s_->erase(0, g_.sector_bytes / 2), StorageStatus::kMisaligned);
  EXPECT_EQ(s_->erase(g_.sector_bytes, g_.size_bytes), StorageStatus::kOutOfRange);
  uint8_t buf[8];
  EXPECT_EQ(s_->read(g_.size_bytes - 4, buf, 8), StorageStatus::kOutOfRange);
  EXPECT_EQ(s_->read(0, nullptr, 8), StorageStatus::kInvalidArgument);
  EXPECT_EQ(read(0, w), std::vector<uint8_t>(a.begin(), a.begin() + w));
  for (uint8_t x : read(w, w)) EXPECT_EQ(x, 0xFF);
  for (uint8_t x : read(g_.size_bytes - 2 * w, 2 * w)) EXPECT_EQ(x, 0xFF);
  EXPECT_EQ(s_->counters().errors, 9u);  // the 9 refused calls above
}

INSTANTIATE_TEST_SUITE_P(
    Backends, StorageContract,
    ::testing::Values(sim_backend("sim_flash_4k_sectors", 4 * 4096, 4096),
                      sim_backend("sim_flash_stm32h7", 2 * SimFlash::kStm32h7SectorBytes,
                                  SimFlash::kStm32h7SectorBytes),
                      file_backend()),
    [](const ::testing::TestParamInfo<StorageBackend>& i) { return i.param.name; });

// What only the simulated flash does: bits only clear, and power cuts leave torn ranges.
TEST(SimFlash, ProgrammingOnlyClearsBits) {
  std::vector<uint8_t> mem(2 * 4096, 0xFF);
  mem[0] = 0x0F;  // a word not erased
  SimFlash f(mem.data(), 8192, 4096);
  uint8_t word[32];
  std::memset(word, 0xF0, sizeof word);
  EXPECT_EQ(f.write(0, word, 32), StorageStatus::kNotErased);
  EXPECT_EQ(f.write(32, word, 32), StorageStatus::kOk);
  EXPECT_EQ(mem[32], 0xF0);
}

TEST(SimFlash, PowerCutLeavesATornWriteAndRefusesEverythingUntilPowerOn) {
  std::vector<uint8_t> mem(2 * 4096, 0xFF);
  SimFlash f(mem.data(), 8192, 4096);
  uint8_t data[64];
  std::memset(data, 0x00, sizeof data);
  f.power_cut_after(40);
  EXPECT_EQ(f.write(0, data, 64), StorageStatus::kPowerLost);
  EXPECT_FALSE(f.powered());
  for (int i = 0; i < 40; ++i) ASSERT_EQ(mem[i], 0x00) << i;
  for (int i = 40; i < 64; ++i) ASSERT_EQ(mem[i], 0xFF) << i;
  uint8_t b;
  EXPECT_EQ(f.read(0, &b, 1), StorageStatus::kPowerLost);
  f.power_on();
  f.power_cut_after(100);
  EXPECT_EQ(f.erase(0, 4096), StorageStatus::kPowerLost);
  for (int i = 0; i < 64; ++i) ASSERT_EQ(mem[i], i < 100 ? 0xFF : 0x00) << i;
  f.power_on();
  EXPECT_EQ(f.erase(0, 4096), StorageStatus::kOk);
  for (int i = 0; i < 64; ++i) ASSERT_EQ(mem[i], 0xFF);
}

TEST(SimFlash, InvalidGeometryRefusesEveryCall) {
  std::vector<uint8_t> mem(1000, 0xFF);
  SimFlash f(mem.data(), 1000, 4096);  // size not a multiple of the sector
  EXPECT_FALSE(f.valid());
  uint8_t b;
  EXPECT_EQ(f.read(0, &b, 1), StorageStatus::kInvalidArgument);
}

}  // namespace
}  // namespace curio::hal
