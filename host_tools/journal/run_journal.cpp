// A run's journal file on the host (host_tools/journal/run_journal.hpp).
#include "host_tools/journal/run_journal.hpp"

#include "firmware/journal/replay.hpp"

namespace curio::journal::host {

std::string describe(const JournalScan& scan) {
  switch (scan.status) {
    case JournalStatus::kOk: {
      std::string s = describe(scan.header.identity) + ": " + std::to_string(scan.episodes) +
                      " episodes journaled";
      if (scan.torn_tail)
        s += "; torn record at slot " + std::to_string(scan.torn_first) + " (" +
             to_string(scan.torn_reason) + ") dropped";
      if (scan.acknowledged_slots > 0)
        s += "; " + std::to_string(scan.acknowledged_slots) + " earlier torn slot(s) skipped";
      return s;
    }
    case JournalStatus::kNoJournal:
      return "no journal";
    case JournalStatus::kTornHeader:
      return "torn header (cut while the journal was being created; no episode in it)";
    case JournalStatus::kCorruptHeader:
      return std::string("corrupt header (") + to_string(scan.bad_reason) + ")";
    case JournalStatus::kUnsupportedVersion:
      return "journal format version " + std::to_string(scan.header.version) +
             " (this build reads versions 1 and " + std::to_string(kVersion) + ")";
    case JournalStatus::kCorrupt:
      return "record " + std::to_string(scan.bad_slot) + " is corrupt (" +
             to_string(scan.bad_reason) + ") and " + std::to_string(scan.episodes) +
             " good episodes precede it; records follow it, so it is not a torn tail";
    case JournalStatus::kStorageError:
      return std::string("storage error: ") + hal::to_string(scan.storage_status);
    default:
      return to_string(scan.status);
  }
}

std::unique_ptr<RunJournal> RunJournal::open(const std::string& path, std::string* error,
                                             uint32_t sync_every) {
  auto j = std::unique_ptr<RunJournal>(new RunJournal());
  j->storage_ = hal::PosixFileStorage::open(path, error);
  if (!j->storage_) return nullptr;
  j->path_ = path;
  j->sync_every_ = sync_every;
  j->scan_ = scan_journal(*j->storage_);
  return j;
}

bool RunJournal::start(const RunIdentity& identity, std::string* error) {
  const JournalStatus s = writer_.create(storage_.get(), identity, sync_every_);
  if (s != JournalStatus::kOk) {
    if (error)
      *error = path_ + ": cannot create the journal: " + to_string(s) + " (" +
               hal::to_string(writer_.storage_status()) + ")";
    return false;
  }
  scan_ = scan_journal(*storage_);
  return true;
}

bool RunJournal::resume(const RunIdentity& identity, Explorer* explorer,
                        const std::function<void(const EpisodeEntry&, const Explorer&)>& on_episode,
                        std::string* error, std::string* notice) {
  auto fail = [&](const std::string& why) {
    if (error) *error = path_ + ": " + why;
    return false;
  };
  if (scan_.status != JournalStatus::kOk)
    return fail("cannot resume: " + describe(scan_) + "; nothing was changed");
  const std::string diff = describe_difference(scan_.header.identity, identity);
  if (!diff.empty()) return fail("cannot resume: " + diff + "; nothing was changed");
  JournalReader reader;
  if (reader.open(storage_.get(), scan_) != JournalStatus::kOk) return fail("cannot read");
  struct Observer final : ReplayObserver {
    const std::function<void(const EpisodeEntry&, const Explorer&)>* f;
    void on_replayed(const EpisodeEntry& e, const Explorer& x) override {
      if (*f) (*f)(e, x);
    }
  } observer;
  observer.f = &on_episode;
  ReplayReport rep;
  if (const JournalStatus s = replay_journal(reader, *explorer, &observer, &rep);
      s != JournalStatus::kOk)
    return fail("replay failed at episode " + std::to_string(rep.episode) + ": " + to_string(s) +
                (rep.what[0] ? std::string(" (") + rep.what + ")" : std::string()) +
                "; nothing was changed");
  if (const JournalStatus s = writer_.resume(storage_.get(), scan_, sync_every_);
      s != JournalStatus::kOk)
    return fail(std::string("cannot continue the journal: ") + to_string(s));
  if (notice) *notice = describe(scan_);
  return true;
}

bool RunJournal::append(const EpisodeEntry& entry, std::string* error) {
  const JournalStatus s = writer_.append(entry);
  if (s == JournalStatus::kOk) return true;
  if (error) *error = write_failure(entry.episode);
  return false;
}

std::string RunJournal::write_failure(uint32_t episode) const {
  const int err = storage_->last_errno();
  return path_ + ": cannot journal episode " + std::to_string(episode) + ": " +
         (err != 0 ? std::string(std::strerror(err))
                   : std::string(hal::to_string(writer_.storage_status())));
}

}  // namespace curio::journal::host
