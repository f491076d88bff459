// Append storage with flash semantics: the one narrow interface the exploration journal
// (firmware/journal/) writes through, on the host (a file, hal/host/posix_file_storage.hpp) and
// on a microcontroller (NOR flash; hal/sim_flash.hpp simulates an STM32H7-class part in RAM).
// Shaped like Zephyr's flash API: a const geometry, then read / write / erase on byte offsets,
// every call returning a status code.
//
// Contract (tests/hal/storage_contract.cpp runs it against every backend):
//   - geometry() never changes: size_bytes, sector_bytes (erase unit, divides size_bytes),
//     write_block_bytes (program unit, divides sector_bytes), erased_value (0xFF).
//   - read(offset, len): any range inside [0, size_bytes); erased bytes read erased_value.
//   - write(offset, len): offset and len multiples of write_block_bytes; every write block in
//     the range must be erased (all erased_value) or the call fails with kNotErased and changes
//     nothing. A write block is programmed once until its sector is erased again.
//   - erase(offset, len): whole sectors (offset, len multiples of sector_bytes); afterwards
//     they read erased_value.
//   - sync(): everything written so far survives a power cut (file: fdatasync; flash: no-op,
//     programming is synchronous).
//   - out-of-range or misaligned calls fail (kOutOfRange, kMisaligned) and change nothing.
// A power cut in the middle of write() or erase() may leave the range torn: some bytes new,
// the rest old (hal/sim_flash.hpp makes that happen at any chosen byte).
#pragma once
#include <cstdint>

namespace curio::hal {

enum class StorageStatus : uint8_t {
  kOk = 0,
  kOutOfRange,       // offset + len beyond size_bytes
  kMisaligned,       // write not on write blocks, erase not on sectors
  kNotErased,        // write over a write block that is not erased; nothing written
  kIoError,          // the backend failed (file I/O error, flash controller error)
  kPowerLost,        // simulated power cut: the operation stopped part way (sim_flash)
  kInvalidArgument,  // null buffer with len > 0
};

constexpr const char* to_string(StorageStatus s) {
  switch (s) {
    case StorageStatus::kOk:
      return "ok";
    case StorageStatus::kOutOfRange:
      return "out_of_range";
    case StorageStatus::kMisaligned:
      return "misaligned";
    case StorageStatus::kNotErased:
      return "not_erased";
    case StorageStatus::kIoError:
      return "io_error";
    case StorageStatus::kPowerLost:
      return "power_lost";
    case StorageStatus::kInvalidArgument:
      return "invalid_argument";
  }
  return "unknown";
}

struct StorageGeometry {
  uint32_t size_bytes = 0;
  uint32_t sector_bytes = 0;       // erase unit
  uint32_t write_block_bytes = 0;  // program unit (STM32H7: 32-byte flash word)
  uint8_t erased_value = 0xFF;
};

struct StorageCounters {
  uint64_t reads = 0;
  uint64_t writes = 0;
  uint64_t erases = 0;  // erase() calls
  uint64_t syncs = 0;
  uint64_t bytes_written = 0;
  uint64_t sectors_erased = 0;
  uint64_t errors = 0;  // calls that returned anything but kOk
};

class Storage {
 public:
  virtual ~Storage() = default;
  virtual const StorageGeometry& geometry() const = 0;
  virtual StorageStatus read(uint32_t offset, void* dst, uint32_t len) = 0;
  virtual StorageStatus write(uint32_t offset, const void* src, uint32_t len) = 0;
  virtual StorageStatus erase(uint32_t offset, uint32_t len) = 0;
  virtual StorageStatus sync() = 0;
  const StorageCounters& counters() const { return counters_; }

 protected:
  // Range and alignment checks every backend applies first (kOk: go ahead).
  StorageStatus check_range(uint32_t offset, uint32_t len, uint32_t align) const {
    const StorageGeometry& g = geometry();
    if (offset > g.size_bytes || len > g.size_bytes - offset) return StorageStatus::kOutOfRange;
    if (align > 1 && (offset % align != 0 || len % align != 0)) return StorageStatus::kMisaligned;
    return StorageStatus::kOk;
  }
  StorageStatus count(StorageStatus s) {
    if (s != StorageStatus::kOk) ++counters_.errors;
    return s;
  }
  StorageCounters counters_;
};

}  // namespace curio::hal
