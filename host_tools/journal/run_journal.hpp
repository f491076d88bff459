// A run's journal file on the host (curio-controller --resume; curio-lab can use the same):
// <out>/journal.bin through hal::PosixFileStorage, the run's identity from its lab::RunSpec
// (run_identity.hpp), and resume = scan + identity check + replay into a fresh Explorer + writer positioned after
// the last good record.
//
//   auto j = host::RunJournal::open(out_dir + "/journal.bin", &error);   // creates if absent
//   const RunIdentity id = host::identity_of(spec, explorer_config, physics);
//   if (resuming) {
//     if (!j->resume(id, explorer.get(), on_episode, &error)) ... // error names the difference,
//   } else if (!j->start(id, &error)) ...                         // e.g. "journal is seed 3,
//   ... after each observe():  j->append(entry, &error)           //  this run is seed 4"
//
// fsync policy: fdatasync after every record by default (sync_every = 1): a SIGKILL or a
// power cut loses at most the episode in flight. tests/bench/bench_journal.cpp measures it.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "firmware/explore/explorer.hpp"
#include "firmware/journal/journal.hpp"
#include "hal/host/posix_file_storage.hpp"
#include "host_tools/experiment/run.hpp"
#include "host_tools/journal/run_identity.hpp"

namespace curio::journal::host {

inline constexpr const char* kJournalFileName = "journal.bin";

// "1234 episodes journaled; torn record at slot 1234 dropped" etc.
std::string describe(const JournalScan& scan);

class RunJournal {
 public:
  // Opens `path` (created empty if absent). sync_every: fdatasync after every this many records.
  static std::unique_ptr<RunJournal> open(const std::string& path, std::string* error,
                                          uint32_t sync_every = 1);

  const JournalScan& scan() const { return scan_; }
  bool has_journal() const { return scan_.status != JournalStatus::kNoJournal; }

  // A new journal (erases whatever the file held).
  bool start(const RunIdentity& identity, std::string* error);

  // Continues the journal: refuses another run's journal (naming the difference), corruption
  // before the tail (naming the slot), replays every journaled episode into `explorer` (must be
  // freshly initialised with the run's config), calling on_episode after each, then positions
  // the writer after the last good record (a torn tail is dropped and noted in *notice).
  bool resume(const RunIdentity& identity, Explorer* explorer,
              const std::function<void(const EpisodeEntry&, const Explorer&)>& on_episode,
              std::string* error, std::string* notice = nullptr);

  bool append(const EpisodeEntry& entry, std::string* error);
  // Why the last append or sync failed, for a message: "<path>: cannot write episode 3135:
  // No space left on device" (the file's errno where the storage had one).
  std::string write_failure(uint32_t episode) const;
  JournalWriter& writer() { return writer_; }
  hal::PosixFileStorage& storage() { return *storage_; }

 private:
  std::unique_ptr<hal::PosixFileStorage> storage_;
  std::string path_;
  JournalScan scan_;
  JournalWriter writer_;
  uint32_t sync_every_ = 1;
};

}  // namespace curio::journal::host
