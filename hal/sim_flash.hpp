// A NOR flash simulated in RAM with the semantics of an STM32H7-class part, for tests that
// cut power at any byte. Firmware-clean (no heap: the caller supplies the memory), so it
// builds for Cortex-M7 too.
//   - sectors of 128 KiB (erase unit; erase sets every byte to 0xFF),
//   - 32-byte flash words (256 bits; program unit): programming only clears bits
//     (new = old AND data) and a word is programmed once: a word that is not all 0xFF is
//     refused (kNotErased; on the real part a second program corrupts its ECC),
//   - power cut: power_cut_after(n) lets n more bytes change (program or erase, in address
//     order), then the operation in progress stops with kPowerLost, leaving its range torn
//     (bytes before the cut new, after it old), and every call fails with kPowerLost until
//     power_on().
// Geometry is configurable (tests use smaller sectors to keep power-cut sweeps short).
#pragma once
#include <cstdint>

#include "hal/storage.hpp"

namespace curio::hal {

class SimFlash final : public Storage {
 public:
  static constexpr uint32_t kStm32h7SectorBytes = 128u * 1024u;
  static constexpr uint32_t kStm32h7WordBytes = 32;
  static constexpr uint64_t kNoCut = ~uint64_t{0};

  // `memory` (size_bytes) is the flash array; its content is kept (a "powered-off" flash
  // survives re-construction). Invalid geometry → every call fails with kInvalidArgument.
  SimFlash(uint8_t* memory, uint32_t size_bytes, uint32_t sector_bytes = kStm32h7SectorBytes,
           uint32_t word_bytes = kStm32h7WordBytes);

  const StorageGeometry& geometry() const override { return geometry_; }
  StorageStatus read(uint32_t offset, void* dst, uint32_t len) override;
  StorageStatus write(uint32_t offset, const void* src, uint32_t len) override;
  StorageStatus erase(uint32_t offset, uint32_t len) override;
  StorageStatus sync() override;

  // Power cut after `bytes` more byte changes (kNoCut: never).
  void power_cut_after(uint64_t bytes) {
    cut_budget_ = bytes;
    powered_ = true;
  }
  void power_on() {
    powered_ = true;
    cut_budget_ = kNoCut;
  }
  bool powered() const { return powered_; }
  uint64_t bytes_changed() const { return bytes_changed_; }  // program + erase, since creation
  bool valid() const { return valid_; }

 private:
  bool spend_byte();  // false: the power goes now

  uint8_t* mem_;
  StorageGeometry geometry_;
  uint64_t cut_budget_ = kNoCut;
  uint64_t bytes_changed_ = 0;
  bool powered_ = true;
  bool valid_ = false;
};

}  // namespace curio::hal
