// The folder a program writes its results into (--out): created if absent, proved writable
// before any work starts, and written by one program at a time.
//
// API:
//   std::string error;
//   auto claim = curio::host::claim_output_folder("out/run", OutputAccess::kExclusive, &error);
//   if (!claim) ... error is one line naming the folder and the reason, e.g.
//       "out/run is in use by curio-controller (PID 4242, started 2026-12-06 16:10:03 UTC);
//        wait for it to end or use another --out"
//       "cannot write into out/run: Read-only file system"
//   ... write the results; the claim is released when `claim` is destroyed or the process ends
//
// How: an advisory flock(2) on the folder itself (an O_DIRECTORY descriptor), so the claim
// writes nothing into the folder and dies with its process (a SIGKILL cannot leave a stale
// lock). kExclusive is a whole run's writer (curio-controller, curio-lab run/paper/merge,
// curio-online); kShared is one of several cooperating writers that each own distinct files
// (the tasks of one Slurm campaign): shared claims coexist, and an exclusive one excludes all.
// The holder named in the message comes from /proc/locks (the PID), /proc/PID/comm and
// /proc/PID/stat (its start time); where /proc does not tell (another PID namespace), the
// message says "another process". Writable: a probe file is created in the folder and removed
// (so a read-only mount, a missing permission or a folder that is a file is found before the
// first episode, not after the last). Linux; flock is local (on NFS it locks per client).
// A file system that has no flock at all (Lustre mounted without -o flock: ENOSYS; some FUSE
// mounts) does not stop the run: the claim is taken unlocked and says so in warning(), which
// the program prints.
#pragma once
#include <memory>
#include <string>

namespace curio::host {

enum class OutputAccess { kExclusive, kShared };

class OutputFolderClaim {
 public:
  ~OutputFolderClaim();
  OutputFolderClaim(const OutputFolderClaim&) = delete;
  OutputFolderClaim& operator=(const OutputFolderClaim&) = delete;
  const std::string& path() const { return path_; }
  // Non-empty when the file system cannot lock: the run goes on with no second-writer guard.
  const std::string& warning() const { return warning_; }

 private:
  friend std::unique_ptr<OutputFolderClaim> claim_output_folder(const std::string&, OutputAccess,
                                                                std::string*);
  OutputFolderClaim(std::string path, int fd, std::string warning)
      : path_(std::move(path)), fd_(fd), warning_(std::move(warning)) {}
  std::string path_;
  int fd_ = -1;
  std::string warning_;
};

// Creates `dir` (and its parents) if absent, checks that a file can be created in it, and
// takes the claim. Null with a one-line *error when any of the three fails; a folder this call
// created is left in place (empty).
std::unique_ptr<OutputFolderClaim> claim_output_folder(const std::string& dir, OutputAccess access,
                                                       std::string* error);

// claim_output_folder for a program's --out, saying on stderr what there is to say, one line
// each: "<program>: <error>" when it fails (null: exit 1), "<program>: warning: <warning>"
// when the file system cannot lock.
std::unique_ptr<OutputFolderClaim> claim_output_folder_or_say(const std::string& program,
                                                              const std::string& dir,
                                                              OutputAccess access);

// "curio-controller (PID 4242, started 2026-12-06 16:10:03 UTC)", or "another process" when
// /proc does not know `pid`. Exposed for tests.
std::string describe_process(long pid);

}  // namespace curio::host
