// hal::Storage on a POSIX file (host): the file is the start of a flash-like region of
// geometry().size_bytes; bytes past its end read as erased (0xFF), erasing the tail truncates.
// Write blocks and sectors are checked exactly as on flash (a write over a non-erased block is
// refused: the journal behaves the same on a file as on an STM32H7).
// fsync policy: sync() is fdatasync(2); write() alone leaves the data in the page cache, which
// survives a SIGKILL of the process but not a power cut. The journal writer calls sync()
// after every record by default (firmware/journal/journal.hpp, sync_every).
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "hal/storage.hpp"

namespace curio::hal {

class PosixFileStorage final : public Storage {
 public:
  static constexpr uint32_t kDefaultSize = 64u << 20;  // 64 MiB of address space
  static constexpr uint32_t kDefaultSector = 4096;
  static constexpr uint32_t kDefaultWriteBlock = 32;  // as the STM32H7 flash word

  // Opens (creating if absent) `path`; null with *error set on failure.
  static std::unique_ptr<PosixFileStorage> open(const std::string& path, std::string* error,
                                                StorageGeometry geometry = {kDefaultSize,
                                                                            kDefaultSector,
                                                                            kDefaultWriteBlock,
                                                                            0xFF});
  ~PosixFileStorage() override;
  PosixFileStorage(const PosixFileStorage&) = delete;
  PosixFileStorage& operator=(const PosixFileStorage&) = delete;

  const StorageGeometry& geometry() const override { return geometry_; }
  StorageStatus read(uint32_t offset, void* dst, uint32_t len) override;
  StorageStatus write(uint32_t offset, const void* src, uint32_t len) override;
  StorageStatus erase(uint32_t offset, uint32_t len) override;
  StorageStatus sync() override;

  const std::string& path() const { return path_; }
  int last_errno() const { return errno_; }
  bool created() const { return created_; }  // the file did not exist before open()

  // false: sync() only counts (no fdatasync). For a journal whose loss costs little (curio-lab's
  // simulated runs, redone from their first episode): a kill still loses nothing, a power
  // cut may lose the file's tail.
  void set_fdatasync(bool enabled) { fdatasync_ = enabled; }

 private:
  PosixFileStorage(int fd, std::string path, StorageGeometry g, bool created);
  int fd_ = -1;
  std::string path_;
  StorageGeometry geometry_;
  uint64_t file_size_ = 0;
  int errno_ = 0;
  bool created_ = false;
  bool fdatasync_ = true;
};

}  // namespace curio::hal
