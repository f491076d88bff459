#include "host_tools/common/bounded_read.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace curio::host {
namespace {

std::string kind_of(mode_t mode) {
  if (S_ISREG(mode)) return "";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISLNK(mode)) return "a symbolic link";
  return "not a regular file";
}

std::string mib(uint64_t bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f MiB", static_cast<double>(bytes) / (1 << 20));
  return buf;
}

}  // namespace

std::string special_file_kind(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return "";
  return kind_of(st.st_mode);
}

bool read_file_bounded(const std::string& path, uint64_t limit, std::string* bytes,
                       std::string* error, const char* what) {
  bytes->clear();
  // O_NONBLOCK: opening a FIFO with no writer must not hang; it is refused below.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    *error = path + ": cannot open " + what + " (" + std::strerror(errno) + ")";
    return false;
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    *error = path + ": cannot stat " + what + " (" + std::strerror(errno) + ")";
    ::close(fd);
    return false;
  }
  if (const std::string kind = kind_of(st.st_mode); !kind.empty()) {
    *error = path + ": " + kind + ", not a regular file (a " + what + " was expected)";
    ::close(fd);
    return false;
  }
  const auto size = static_cast<uint64_t>(st.st_size);
  if (size > limit) {
    *error = path + ": " + mib(size) + ", more than the " + mib(limit) + " a " + what +
             " may have";
    ::close(fd);
    return false;
  }
  bytes->resize(static_cast<size_t>(size));
  size_t got = 0;
  for (;;) {  // the file may have grown or shrunk since fstat: read to its end, within the limit
    if (got == bytes->size()) {
      if (bytes->size() >= limit) {
        char probe;
        const ssize_t n = ::read(fd, &probe, 1);
        if (n > 0) {
          *error = path + ": grew past the " + mib(limit) + " a " + what + " may have";
          ::close(fd);
          return false;
        }
        break;
      }
      bytes->resize(static_cast<size_t>(std::min<uint64_t>(limit, bytes->size() + 65536)));
    }
    const ssize_t n = ::read(fd, bytes->data() + got, bytes->size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      *error = path + ": cannot read " + what + " (" + std::strerror(errno) + ")";
      ::close(fd);
      return false;
    }
    if (n == 0) break;
    got += static_cast<size_t>(n);
  }
  bytes->resize(got);
  ::close(fd);
  return true;
}

std::string read_file_bounded_or_throw(const std::string& path, uint64_t limit, const char* what) {
  std::string bytes, error;
  if (!read_file_bounded(path, limit, &bytes, &error, what)) throw std::runtime_error(error);
  return bytes;
}

}  // namespace curio::host
