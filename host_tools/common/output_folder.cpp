#include "host_tools/common/output_folder.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "host_tools/common/atomic_file.hpp"

namespace curio::host {
namespace {

// The PID /proc/locks names for a flock on the file (dev, ino), or -1.
long lock_holder(dev_t dev, ino_t ino) {
  std::ifstream locks("/proc/locks");
  char want[64];
  std::snprintf(want, sizeof want, "%02x:%02x:%lu", major(dev), minor(dev),
                static_cast<unsigned long>(ino));
  std::string line;
  while (std::getline(locks, line)) {
    // "1: FLOCK  ADVISORY  WRITE 1234 08:01:123456 0 EOF" ("1: -> FLOCK ..." for a waiter)
    std::istringstream in(line);
    std::string id, kind, advisory, mode, where;
    long pid = -1;
    if (!(in >> id >> kind) || kind == "->") continue;
    if (!(in >> advisory >> mode >> pid >> where)) continue;
    if (kind == "FLOCK" && where == want) return pid;
  }
  return -1;
}

std::string program_of(long pid) {
  std::ifstream comm("/proc/" + std::to_string(pid) + "/comm");
  std::string name;
  std::getline(comm, name);
  return name;
}

// Seconds since the epoch at which `pid` started, or 0.
std::time_t start_time_of(long pid) {
  std::ifstream stat_file("/proc/" + std::to_string(pid) + "/stat");
  std::string stat((std::istreambuf_iterator<char>(stat_file)), std::istreambuf_iterator<char>());
  const size_t close = stat.rfind(')');  // the command name may hold spaces and parentheses
  if (close == std::string::npos) return 0;
  std::istringstream fields(stat.substr(close + 2));
  std::string field;
  unsigned long long start_ticks = 0;
  for (int i = 3; i <= 22 && fields >> field; ++i)  // field 22: starttime, in clock ticks
    if (i == 22) start_ticks = std::strtoull(field.c_str(), nullptr, 10);
  std::ifstream proc_stat("/proc/stat");
  std::string key;
  unsigned long long boot = 0;
  while (proc_stat >> key)
    if (key == "btime" && proc_stat >> boot) break;
  const long ticks = ::sysconf(_SC_CLK_TCK);
  if (boot == 0 || ticks <= 0 || start_ticks == 0) return 0;
  return static_cast<std::time_t>(boot + start_ticks / static_cast<unsigned long long>(ticks));
}

// Creates and removes a file in `dir`: false with the reason when it cannot.
bool probe_writable(const std::string& dir, std::string* why) {
  const std::string probe = temp_path_for((std::filesystem::path(dir) / ".curio-probe").string());
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    *why = std::strerror(errno);
    return false;
  }
  const bool written = ::write(fd, "x", 1) == 1;
  if (!written) *why = std::strerror(errno);
  ::close(fd);
  ::unlink(probe.c_str());
  return written;
}

}  // namespace

std::string describe_process(long pid) {
  const std::string name = pid > 0 ? program_of(pid) : "";
  if (name.empty()) return "another process";
  std::string out = name + " (PID " + std::to_string(pid);
  if (const std::time_t t = start_time_of(pid)) {
    char when[64];
    std::tm utc{};
    gmtime_r(&t, &utc);
    std::strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S UTC", &utc);
    out += std::string(", started ") + when;
  }
  return out + ")";
}

OutputFolderClaim::~OutputFolderClaim() {
  if (fd_ >= 0) ::close(fd_);  // releases the flock
}

std::unique_ptr<OutputFolderClaim> claim_output_folder(const std::string& dir, OutputAccess access,
                                                       std::string* error) {
  if (dir.empty()) {
    *error = "the output folder is an empty path";
    return nullptr;
  }
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    *error = "cannot create the folder " + dir + ": " + ec.message();
    return nullptr;
  }
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) {
    *error = "cannot open the folder " + dir + ": " + std::strerror(errno);
    return nullptr;
  }
  const int op = (access == OutputAccess::kExclusive ? LOCK_EX : LOCK_SH) | LOCK_NB;
  int rc;
  do rc = ::flock(fd, op);
  while (rc != 0 && errno == EINTR);
  std::string warning;
  if (rc != 0 && (errno == ENOSYS || errno == ENOLCK || errno == EOPNOTSUPP || errno == EINVAL)) {
    warning = "the file system of " + dir + " cannot lock (" + std::strerror(errno) +
              "): nothing stops a second program from writing there at the same time";
    rc = 0;
  }
  if (rc != 0) {
    const int e = errno;
    struct stat st {};
    const long pid = ::fstat(fd, &st) == 0 ? lock_holder(st.st_dev, st.st_ino) : -1;
    ::close(fd);
    *error = e == EWOULDBLOCK ? dir + " is in use by " + describe_process(pid) +
                                    "; wait for it to end or use another --out"
                              : "cannot lock the folder " + dir + ": " + std::strerror(e);
    return nullptr;
  }
  std::string why;
  if (!probe_writable(dir, &why)) {
    ::close(fd);
    *error = "cannot write into " + dir + ": " + why;
    return nullptr;
  }
  return std::unique_ptr<OutputFolderClaim>(new OutputFolderClaim(dir, fd, std::move(warning)));
}

std::unique_ptr<OutputFolderClaim> claim_output_folder_or_say(const std::string& program,
                                                              const std::string& dir,
                                                              OutputAccess access) {
  std::string error;
  auto claim = claim_output_folder(dir, access, &error);
  if (!claim)
    std::fprintf(stderr, "%s: %s\n", program.c_str(), error.c_str());
  else if (!claim->warning().empty())
    std::fprintf(stderr, "%s: warning: %s\n", program.c_str(), claim->warning().c_str());
  return claim;
}

}  // namespace curio::host
