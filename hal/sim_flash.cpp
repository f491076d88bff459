// RAM-simulated STM32H7-class NOR flash (hal/sim_flash.hpp).
#include "hal/sim_flash.hpp"

#include <cstring>

namespace curio::hal {

SimFlash::SimFlash(uint8_t* memory, uint32_t size_bytes, uint32_t sector_bytes,
                   uint32_t word_bytes)
    : mem_(memory), geometry_{size_bytes, sector_bytes, word_bytes, 0xFF} {
  valid_ = memory != nullptr && word_bytes > 0 && sector_bytes >= word_bytes &&
           sector_bytes % word_bytes == 0 && size_bytes > 0 && size_bytes % sector_bytes == 0;
}

bool SimFlash::spend_byte() {
  if (cut_budget_ == 0) {
    powered_ = false;
    return false;
  }
  if (cut_budget_ != kNoCut) --cut_budget_;
  ++bytes_changed_;
  return true;
}

StorageStatus SimFlash::read(uint32_t offset, void* dst, uint32_t len) {
  ++counters_.reads;
  if (!valid_) return count(StorageStatus::kInvalidArgument);
  if (!powered_) return count(StorageStatus::kPowerLost);
  if (dst == nullptr && len > 0) return count(StorageStatus::kInvalidArgument);
  if (const StorageStatus s = check_range(offset, len, 1); s != StorageStatus::kOk) return count(s);
  if (len > 0) std::memcpy(dst, mem_ + offset, len);
  return StorageStatus::kOk;
}

StorageStatus SimFlash::write(uint32_t offset, const void* src, uint32_t len) {
  ++counters_.writes;
  if (!valid_) return count(StorageStatus::kInvalidArgument);
  if (!powered_) return count(StorageStatus::kPowerLost);
  if (src == nullptr && len > 0) return count(StorageStatus::kInvalidArgument);
  const uint32_t word = geometry_.write_block_bytes;
  if (const StorageStatus s = check_range(offset, len, word); s != StorageStatus::kOk)
    return count(s);
  // Every word must be erased before anything is programmed (the call changes nothing else).
  for (uint32_t i = 0; i < len; ++i)
    if (mem_[offset + i] != 0xFF) return count(StorageStatus::kNotErased);
  const auto* in = static_cast<const uint8_t*>(src);
  for (uint32_t i = 0; i < len; ++i) {
    if (!spend_byte()) return count(StorageStatus::kPowerLost);
    mem_[offset + i] = static_cast<uint8_t>(mem_[offset + i] & in[i]);
  }
  counters_.bytes_written += len;
  return StorageStatus::kOk;
}

StorageStatus SimFlash::erase(uint32_t offset, uint32_t len) {
  ++counters_.erases;
  if (!valid_) return count(StorageStatus::kInvalidArgument);
  if (!powered_) return count(StorageStatus::kPowerLost);
  if (const StorageStatus s = check_range(offset, len, geometry_.sector_bytes);
      s != StorageStatus::kOk)
    return count(s);
  for (uint32_t i = 0; i < len; ++i) {
    if (!spend_byte()) return count(StorageStatus::kPowerLost);
    mem_[offset + i] = 0xFF;
    if ((i + 1) % geometry_.sector_bytes == 0) ++counters_.sectors_erased;
  }
  return StorageStatus::kOk;
}

StorageStatus SimFlash::sync() {
  ++counters_.syncs;
  if (!valid_) return count(StorageStatus::kInvalidArgument);
  if (!powered_) return count(StorageStatus::kPowerLost);
  return StorageStatus::kOk;  // programming is synchronous
}

}  // namespace curio::hal
