// Reading a whole input file with a size limit suited to it: a file past the limit, or a path
// that is not a regular file (a directory, a FIFO, a device such as /dev/zero), is refused with
// one line naming the file and the reason, before anything is allocated for it. So no reader
// grows without bound or ends in a bare std::bad_alloc.
//
// API:
//   std::string bytes, error;
//   if (!curio::host::read_file_bounded(path, curio::host::kJsonFileLimit, &bytes, &error))
//     ... error: "<path>: a FIFO, not a regular file" / "<path>: 80.0 MiB, more than the
//         64.0 MiB a <what> may have" / "<path>: cannot open (No such file or directory)"
//   curio::host::read_file_bounded_or_throw(path, limit, "float model")   // std::runtime_error
#pragma once
#include <cstdint>
#include <string>

namespace curio::host {

// Limits by kind of file (each far above what Curio writes: a float model is ~1.5 MiB, a
// summary or meta JSON a few kB, a run record ~1 MiB).
inline constexpr uint64_t kJsonFileLimit = 16ull << 20;    // JSON: meta, counters, summaries
inline constexpr uint64_t kModelFileLimit = 256ull << 20;  // float model (.cfm), weights header
inline constexpr uint64_t kRecordFileLimit = 1ull << 30;   // run records, images

// What kind of file system object `path` is, when it is not a regular file ("a directory",
// "a FIFO", "a character device", "a block device", "a socket", "a symbolic link"); "" for a
// regular file or a path that does not exist. Links are not followed.
std::string special_file_kind(const std::string& path);

// Reads all of the regular file `path` (at most `limit` bytes) into *bytes. `what` names the
// kind of file in the error ("float model"). false with *error.
bool read_file_bounded(const std::string& path, uint64_t limit, std::string* bytes,
                       std::string* error, const char* what = "file");

// The same, throwing std::runtime_error with the error.
std::string read_file_bounded_or_throw(const std::string& path, uint64_t limit,
                                       const char* what = "file");

}  // namespace curio::host
