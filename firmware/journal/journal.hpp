// The exploration journal: an append-only log of observed episodes on a hal::Storage, from
// which the Explorer's whole state is rebuilt by replay (firmware/journal/replay.hpp).
// Format: journal_format.hpp. Firmware-clean: no heap, fixed buffers (one slot), status codes.
//
//   JournalWriter w;
//   w.create(&storage, identity);               // erases the storage, writes the header
//   ... after each Explorer::observe():  w.append(entry);   // one slot, synced every K
//
//   JournalScan scan = scan_journal(storage);   // after a restart: classify what is there
//   if (scan.status == JournalStatus::kOk) {    // (a torn tail is kOk, reported in the scan)
//     replay(...)                               // replay.hpp
//     w.resume(&storage, scan);                 // continue after the last good record
//   }
//
// Guarantees:
//   - append() returns kOk only once the slot is written (and, every sync_every appends,
//     synced): a power cut after that keeps the record.
//   - A power cut during an append leaves at most that one slot torn. scan_journal() finds it
//     by its CRC, drops it and reports it (torn_tail, torn_slots); every earlier record is kept.
//     resume() then writes a skip record naming the torn slot(s) in the next slot (a flash
//     word is programmed once: the torn slot cannot be rewritten), so later scans see the
//     damage acknowledged, not damage found now.
//   - An invalid slot followed by anything other than erased space or a skip record naming
//     it is corruption before the tail: kCorrupt with bad_slot; the writer refuses to resume
//     it, and nothing is overwritten. So is a record that validates but is out of place
//     (another slot's number, an episode out of sequence): a torn write cannot make one.
//   - create() erases sector 0 (the old header) first, then the rest: a cut during create
//     leaves no header that validates, never an old run's header over a half-erased log:
//     kNoJournal, kTornHeader, or kCorruptHeader when the cut fell inside the old header's
//     own bytes and old records still follow it in sector 0 (tests/journal/power_cut*.cpp).
// Non-guarantees: the episode in flight when power is lost is run again; a corrupt header
// makes the journal unreadable (kCorruptHeader), its records are not salvaged.
#pragma once
#include <cstdint>

#include "firmware/journal/journal_format.hpp"
#include "hal/storage.hpp"

namespace curio::journal {

enum class JournalStatus : uint8_t {
  kOk = 0,
  kNoJournal,           // header slot erased: nothing was ever journaled here
  kTornHeader,          // header does not validate and no record follows: a cut during create
  kCorruptHeader,       // header does not validate but records follow it
  kUnsupportedVersion,  // a valid header of another format version
  kCorrupt,             // a slot before the tail does not validate (scan.bad_slot)
  kFull,                // no free slot left
  kStorageError,        // the storage refused a call (scan.storage_status / storage_status())
  kInvalidArgument,     // null storage, outcome_dim out of range, geometry unsupported
  kNotOpen,             // append() before create()/resume()
  kWrongEpisode,        // append() of an episode out of order
  kReplayMismatch,      // replay: the explorer disagrees with a journaled record
};
const char* to_string(JournalStatus s);

struct JournalScan {
  JournalStatus status = JournalStatus::kNoJournal;
  Header header;                 // valid when status is kOk, kCorrupt
  uint32_t slots = 0;            // slot capacity of the storage
  uint32_t episodes = 0;         // episode records 0 .. episodes−1, all valid and in order
  uint32_t next_slot = 0;        // first slot after the last valid record (or torn tail)
  uint32_t last_valid_slot = 0;  // slot after the last valid record (where a skip goes)
  bool torn_tail = false;        // invalid slot(s) at the end, dropped
  uint32_t torn_first = 0;       // first dropped slot
  uint32_t torn_slots = 0;       // how many were dropped
  DecodeResult torn_reason = DecodeResult::kOk;
  uint32_t acknowledged_slots = 0;  // torn slots named by skip records (earlier resumes)
  uint32_t bad_slot = 0;            // kCorrupt: the first slot that does not validate
  DecodeResult bad_reason = DecodeResult::kOk;
  hal::StorageStatus storage_status = hal::StorageStatus::kOk;
};

// Reads the whole journal region and classifies it (changes nothing).
JournalScan scan_journal(hal::Storage& storage);

// Episode records in order, after a kOk scan (skip records and acknowledged slots passed over).
class JournalReader {
 public:
  JournalStatus open(hal::Storage* storage, const JournalScan& scan);
  // Next episode; *end = true (and kOk) after the last one.
  JournalStatus next(EpisodeEntry* entry, bool* end);

 private:
  hal::Storage* storage_ = nullptr;
  JournalScan scan_;
  uint32_t slot_ = 0;
  uint32_t episodes_read_ = 0;
};

struct JournalWriterCounters {
  uint64_t appends = 0;
  uint64_t syncs = 0;
  uint64_t skips_written = 0;
  uint64_t errors = 0;
};

class JournalWriter {
 public:
  // Erases the whole storage (sector 0 first), writes and syncs the header. sync_every: the
  // storage is synced after every this many appends (1: every record; 0: only by sync()).
  JournalStatus create(hal::Storage* storage, const RunIdentity& identity, uint32_t sync_every = 1);
  // Continues after a kOk scan; writes (and syncs) a skip record first if the tail was torn.
  JournalStatus resume(hal::Storage* storage, const JournalScan& scan, uint32_t sync_every = 1);
  // Appends episode entry.episode (must be episodes()).
  JournalStatus append(const EpisodeEntry& entry);
  JournalStatus sync();

  bool open() const { return storage_ != nullptr; }
  uint32_t episodes() const { return episodes_; }
  uint32_t next_slot() const { return slot_; }
  uint32_t slots() const { return slots_; }
  uint32_t record_stride() const { return header_.record_stride; }
  uint32_t header_stride() const { return header_.header_stride; }
  const Header& header() const { return header_; }
  hal::StorageStatus storage_status() const { return storage_status_; }
  const JournalWriterCounters& counters() const { return counters_; }

 private:
  JournalStatus write_slot(const Record& r);
  JournalStatus fail(JournalStatus s) {
    ++counters_.errors;
    return s;
  }

  hal::Storage* storage_ = nullptr;
  Header header_;
  uint32_t slots_ = 0;
  uint32_t slot_ = 0;
  uint32_t episodes_ = 0;
  uint32_t sync_every_ = 1;
  uint32_t unsynced_ = 0;
  hal::StorageStatus storage_status_ = hal::StorageStatus::kOk;
  JournalWriterCounters counters_;
};

// Slot capacity of a storage for an outcome dimension and a header version (0 if the geometry
// is unsupported). The two versions' headers take the same stride on 32-byte flash words.
uint32_t slot_capacity(const hal::StorageGeometry& g, int outcome_dim,
                       uint16_t version = kVersionSpec);

}  // namespace curio::journal
