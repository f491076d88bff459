// Result files written so that a kill, a crash or a power cut at any instant leaves the old
// file or the new one at its path, never half of one.
//
// API:
//   std::string error;
//   if (!curio::host::write_file_atomically("out/summary.json", text, &error)) ... error names
//       the file and the reason; the old file (if any) is untouched
//   // A file another program writes (gnuplot's PNG, libpng):
//   const std::string tmp = curio::host::temp_path_for("out/plot.png");
//   ... let it write tmp ...
//   curio::host::commit_temp(tmp, "out/plot.png", &error);   // or remove_temp(tmp) on failure
//
// How: the bytes go to "<path>.tmp.<pid>.<n>" in the same folder (same file system, so the
// rename is atomic; <n> makes concurrent writers of one process distinct), which is flushed
// and fsync'ed, then renamed over <path>. fsync policy: the file's data are synced before the
// rename, so a power cut cannot leave a renamed but empty file; the folder is not synced, so
// after a power cut the rename itself may be lost (the old file is then still there, whole).
// The cost is one fsync per file: about 1 ms each here, 0.21 s for the 210 files of an
// EFR paper campaign's report (docs/lab.md, "Costs measured"). A temporary file left by a SIGKILL is named *.tmp.*; readers ignore it.
#pragma once
#include <string>
#include <string_view>

namespace curio::host {

// Writes `bytes` to `path` as described above. false with *error (the file is unchanged). A
// symbolic link, FIFO, device or directory at `path` is refused, naming it: never replaced,
// never written through.
bool write_file_atomically(const std::string& path, std::string_view bytes, std::string* error);

// The same for code that reports failures by exception (curio-train, curio-online): throws
// std::runtime_error with that error.
void write_file_atomically_or_throw(const std::string& path, std::string_view bytes);

// A fresh temporary path beside `path` for a file another writer produces.
std::string temp_path_for(const std::string& path);

// fsync's `tmp` and renames it to `path`; on failure removes `tmp` and returns false with *error.
bool commit_temp(const std::string& tmp, const std::string& path, std::string* error);

// Removes a temporary file that will not be committed (no error if it does not exist).
void remove_temp(const std::string& tmp);

// Whether a file name is one of temp_path_for's ("x.csv.tmp.123.4"): left by a killed writer.
bool is_temp_name(std::string_view file_name);

}  // namespace curio::host
