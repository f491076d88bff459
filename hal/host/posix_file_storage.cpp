// hal::Storage on a POSIX file (hal/host/posix_file_storage.hpp).
#include "hal/host/posix_file_storage.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <vector>

namespace curio::hal {

namespace {

bool geometry_ok(const StorageGeometry& g) {
  return g.write_block_bytes > 0 && g.sector_bytes >= g.write_block_bytes &&
         g.sector_bytes % g.write_block_bytes == 0 && g.size_bytes > 0 &&
         g.size_bytes % g.sector_bytes == 0;
}

// pread/pwrite the whole range (they may return short).
bool pread_all(int fd, uint8_t* dst, size_t len, off_t at) {
  while (len > 0) {
    const ssize_t n = ::pread(fd, dst, len, at);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    dst += n;
    len -= static_cast<size_t>(n);
    at += n;
  }
  return true;
}

bool pwrite_all(int fd, const uint8_t* src, size_t len, off_t at) {
  while (len > 0) {
    const ssize_t n = ::pwrite(fd, src, len, at);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    src += n;
    len -= static_cast<size_t>(n);
    at += n;
  }
  return true;
}

// fsync the folder holding `path` so a newly created file's name is durable too.
void sync_parent(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash + 1);
  const int d = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (d >= 0) {
    ::fsync(d);
    ::close(d);
  }
}

}  // namespace

std::unique_ptr<PosixFileStorage> PosixFileStorage::open(const std::string& path,
                                                         std::string* error,
                                                         StorageGeometry geometry) {
  if (!geometry_ok(geometry)) {
    if (error) *error = "invalid storage geometry";
    return nullptr;
  }
  struct stat st {};
  const bool existed = ::stat(path.c_str(), &st) == 0;
  // O_NOFOLLOW: a symbolic link is refused, never written through (as root, to any file);
  // O_NONBLOCK: a FIFO does not hang the open; it is refused below, as a device is.
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0644);
  if (fd < 0) {
    if (error)
      *error = errno == ELOOP ? "cannot open " + path +
                                    ": it is a symbolic link; refusing to follow it (use the "
                                    "file it points to, or another path)"
               : errno == EISDIR ? "cannot open " + path + ": it is a directory, not a file"
                                 : "cannot open " + path + ": " + std::strerror(errno);
    return nullptr;
  }
  if (!existed) sync_parent(path);
  std::unique_ptr<PosixFileStorage> s(new PosixFileStorage(fd, path, geometry, !existed));
  if (::fstat(fd, &st) != 0) {
    if (error) *error = "cannot stat " + path + ": " + std::strerror(errno);
    return nullptr;
  }
  if (!S_ISREG(st.st_mode)) {
    if (error)
      *error = "cannot open " + path + ": it is " +
               (S_ISFIFO(st.st_mode)  ? "a FIFO"
                : S_ISCHR(st.st_mode) ? "a character device"
                : S_ISBLK(st.st_mode) ? "a block device"
                : S_ISSOCK(st.st_mode) ? "a socket"
                                       : "not a regular file") +
               ", not a regular file";
    return nullptr;
  }
  s->file_size_ = static_cast<uint64_t>(st.st_size);
  if (s->file_size_ > geometry.size_bytes) {
    if (error) *error = path + " is larger than the storage geometry";
    return nullptr;
  }
  return s;
}

PosixFileStorage::PosixFileStorage(int fd, std::string path, StorageGeometry g, bool created)
    : fd_(fd), path_(std::move(path)), geometry_(g), created_(created) {}

PosixFileStorage::~PosixFileStorage() {
  if (fd_ >= 0) ::close(fd_);
}

StorageStatus PosixFileStorage::read(uint32_t offset, void* dst, uint32_t len) {
  ++counters_.reads;
  if (dst == nullptr && len > 0) return count(StorageStatus::kInvalidArgument);
  if (const StorageStatus s = check_range(offset, len, 1); s != StorageStatus::kOk) return count(s);
  auto* out = static_cast<uint8_t*>(dst);
  // The part inside the file, then erased bytes past its end.
  const uint64_t in_file =
      offset >= file_size_ ? 0 : std::min<uint64_t>(len, file_size_ - offset);
  if (in_file > 0 && !pread_all(fd_, out, in_file, static_cast<off_t>(offset))) {
    errno_ = errno;
    return count(StorageStatus::kIoError);
  }
  std::memset(out + in_file, geometry_.erased_value, len - in_file);
  return StorageStatus::kOk;
}

StorageStatus PosixFileStorage::write(uint32_t offset, const void* src, uint32_t len) {
  ++counters_.writes;
  if (src == nullptr && len > 0) return count(StorageStatus::kInvalidArgument);
  if (const StorageStatus s = check_range(offset, len, geometry_.write_block_bytes);
      s != StorageStatus::kOk)
    return count(s);
  if (len == 0) return StorageStatus::kOk;
  // As on flash: only erased blocks may be written (the journal must not depend on
  // overwrites a NOR part cannot do).
  if (offset < file_size_) {
    std::vector<uint8_t> old(len);
    if (const StorageStatus s = read(offset, old.data(), len); s != StorageStatus::kOk) return s;
    for (uint8_t b : old)
      if (b != geometry_.erased_value) return count(StorageStatus::kNotErased);
  }
  // A write past the end fills the gap with erased bytes (a hole would read as zeros).
  if (offset > file_size_) {
    const std::vector<uint8_t> ff(offset - file_size_, geometry_.erased_value);
    if (!pwrite_all(fd_, ff.data(), ff.size(), static_cast<off_t>(file_size_))) {
      errno_ = errno;
      return count(StorageStatus::kIoError);
    }
    file_size_ = offset;
  }
  if (!pwrite_all(fd_, static_cast<const uint8_t*>(src), len, static_cast<off_t>(offset))) {
    errno_ = errno;
    return count(StorageStatus::kIoError);
  }
  file_size_ = std::max<uint64_t>(file_size_, uint64_t{offset} + len);
  counters_.bytes_written += len;
  return StorageStatus::kOk;
}

StorageStatus PosixFileStorage::erase(uint32_t offset, uint32_t len) {
  ++counters_.erases;
  if (const StorageStatus s = check_range(offset, len, geometry_.sector_bytes);
      s != StorageStatus::kOk)
    return count(s);
  const uint64_t end = uint64_t{offset} + len;
  if (offset < file_size_) {
    if (end >= file_size_) {
      // Erasing through the end of the file: truncate (bytes past the end read erased).
      if (::ftruncate(fd_, static_cast<off_t>(offset)) != 0) {
        errno_ = errno;
        return count(StorageStatus::kIoError);
      }
      file_size_ = offset;
    } else {
      const std::vector<uint8_t> ff(len, geometry_.erased_value);
      if (!pwrite_all(fd_, ff.data(), len, static_cast<off_t>(offset))) {
        errno_ = errno;
        return count(StorageStatus::kIoError);
      }
    }
  }
  counters_.sectors_erased += len / geometry_.sector_bytes;
  return StorageStatus::kOk;
}

StorageStatus PosixFileStorage::sync() {
  ++counters_.syncs;
  if (fdatasync_ && ::fdatasync(fd_) != 0) {
    errno_ = errno;
    return count(StorageStatus::kIoError);
  }
  return StorageStatus::kOk;
}

}  // namespace curio::hal
