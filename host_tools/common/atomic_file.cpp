#include "host_tools/common/atomic_file.hpp"

#include "host_tools/common/bounded_read.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace curio::host {
namespace {

std::atomic<unsigned long> g_sequence{0};

std::string errno_text() { return std::strerror(errno); }

// Writes all of `bytes` to `fd` (write() may write less than asked).
bool write_all(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    bytes.remove_prefix(static_cast<size_t>(n));
  }
  return true;
}

}  // namespace

std::string temp_path_for(const std::string& path) {
  return path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(g_sequence++);
}

void remove_temp(const std::string& tmp) { ::unlink(tmp.c_str()); }

bool commit_temp(const std::string& tmp, const std::string& path, std::string* error) {
  if (const std::string kind = special_file_kind(path); !kind.empty()) {
    remove_temp(tmp);
    *error = "cannot write " + path + ": it is " + kind +
             ", not a regular file; refusing to replace it (remove it or choose another path)";
    return false;
  }
  const int fd = ::open(tmp.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    *error = "cannot write " + path + ": " + tmp + " is missing (" + errno_text() + ")";
    return false;
  }
  const bool synced = ::fsync(fd) == 0;
  const std::string why = synced ? "" : errno_text();
  ::close(fd);
  if (!synced) {
    remove_temp(tmp);
    *error = "cannot write " + path + ": fsync failed (" + why + ")";
    return false;
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string e = errno_text();
    remove_temp(tmp);
    *error = "cannot write " + path + ": rename failed (" + e + ")";
    return false;
  }
  return true;
}

bool write_file_atomically(const std::string& path, std::string_view bytes, std::string* error) {
  if (const std::string kind = special_file_kind(path); !kind.empty()) {
    *error = "cannot write " + path + ": it is " + kind +
             ", not a regular file; refusing to replace it (remove it or choose another path)";
    return false;
  }
  const std::string tmp = temp_path_for(path);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (fd < 0) {
    *error = "cannot write " + path + " (" + errno_text() + ")";
    return false;
  }
  const bool written = write_all(fd, bytes);
  const std::string why = written ? "" : errno_text();
  if (::close(fd) != 0 || !written) {
    remove_temp(tmp);
    *error = "cannot write " + path + " (" + (written ? errno_text() : why) + ")";
    return false;
  }
  return commit_temp(tmp, path, error);  // fsync, then rename over `path`
}

void write_file_atomically_or_throw(const std::string& path, std::string_view bytes) {
  std::string error;
  if (!write_file_atomically(path, bytes, &error)) throw std::runtime_error(error);
}

bool is_temp_name(std::string_view name) {
  const size_t at = name.rfind(".tmp.");
  if (at == std::string_view::npos || at == 0) return false;
  const std::string_view tail = name.substr(at + 5);  // "<pid>.<n>"
  const size_t dot = tail.find('.');
  if (dot == std::string_view::npos || dot == 0 || dot + 1 == tail.size()) return false;
  for (size_t i = 0; i < tail.size(); ++i)
    if (i != dot && (tail[i] < '0' || tail[i] > '9')) return false;
  return true;
}

}  // namespace curio::host
