// Journal scan, reader and writer (firmware/journal/journal.hpp).
#include "firmware/journal/journal.hpp"

#include <cstring>

namespace curio::journal {

namespace {

// Header block (of a header `version`) and slot sizes for a geometry (0: unsupported).
uint32_t header_stride_for(const hal::StorageGeometry& g, uint16_t version) {
  const size_t bytes = header_bytes(version);
  if (bytes == 0 || g.write_block_bytes == 0 || g.write_block_bytes > kMaxBlockBytes) return 0;
  const uint32_t s = round_up(static_cast<uint32_t>(bytes), g.write_block_bytes);
  return s <= kMaxBlockBytes && s <= g.sector_bytes ? s : 0;
}

uint32_t record_stride_for(const hal::StorageGeometry& g, int outcome_dim) {
  if (outcome_dim < 1 || outcome_dim > kMaxOutcomeDim || g.write_block_bytes == 0) return 0;
  const uint32_t s = round_up(record_bytes(outcome_dim), g.write_block_bytes);
  return s <= kMaxBlockBytes ? s : 0;
}

bool erased(const uint8_t* p, uint32_t n) {
  for (uint32_t i = 0; i < n; ++i)
    if (p[i] != 0xFF) return false;
  return true;
}

// Whether [from, to) of the storage reads all erased (a fixed buffer at a time).
bool range_erased(hal::Storage& s, uint32_t from, uint32_t to, hal::StorageStatus* status) {
  uint8_t buf[kMaxBlockBytes];
  while (from < to) {
    const uint32_t n = to - from < kMaxBlockBytes ? to - from : kMaxBlockBytes;
    *status = s.read(from, buf, n);
    if (*status != hal::StorageStatus::kOk) return false;
    if (!erased(buf, n)) return false;
    from += n;
  }
  return true;
}

}  // namespace

const char* to_string(JournalStatus s) {
  switch (s) {
    case JournalStatus::kOk:
      return "ok";
    case JournalStatus::kNoJournal:
      return "no_journal";
    case JournalStatus::kTornHeader:
      return "torn_header";
    case JournalStatus::kCorruptHeader:
      return "corrupt_header";
    case JournalStatus::kUnsupportedVersion:
      return "unsupported_version";
    case JournalStatus::kCorrupt:
      return "corrupt";
    case JournalStatus::kFull:
      return "full";
    case JournalStatus::kStorageError:
      return "storage_error";
    case JournalStatus::kInvalidArgument:
      return "invalid_argument";
    case JournalStatus::kNotOpen:
      return "not_open";
    case JournalStatus::kWrongEpisode:
      return "wrong_episode";
    case JournalStatus::kReplayMismatch:
      return "replay_mismatch";
  }
  return "unknown";
}

uint32_t slot_capacity(const hal::StorageGeometry& g, int outcome_dim, uint16_t version) {
  const uint32_t h = header_stride_for(g, version);
  const uint32_t r = record_stride_for(g, outcome_dim);
  if (h == 0 || r == 0 || g.size_bytes < h) return 0;
  return (g.size_bytes - h) / r;
}

JournalScan scan_journal(hal::Storage& storage) {
  JournalScan scan;
  const hal::StorageGeometry& g = storage.geometry();
  // Read as much as the largest header takes; the header's version says how much is its own.
  const uint32_t hstride = header_stride_for(g, kVersion);
  if (hstride == 0) {
    scan.status = JournalStatus::kInvalidArgument;
    return scan;
  }
  uint8_t buf[kMaxBlockBytes];
  auto storage_error = [&](hal::StorageStatus s) {
    scan.storage_status = s;
    scan.status = JournalStatus::kStorageError;
    return scan;
  };
  if (const hal::StorageStatus s = storage.read(0, buf, hstride); s != hal::StorageStatus::kOk)
    return storage_error(s);
  const DecodeResult h = decode_header(buf, hstride, &scan.header);
  if (h != DecodeResult::kOk) {
    scan.bad_reason = h;
    if (h == DecodeResult::kErased) {
      scan.status = JournalStatus::kNoJournal;
    } else if (h == DecodeResult::kBadVersion) {
      scan.status = JournalStatus::kUnsupportedVersion;
    } else {
      // Torn while being created (nothing after it) or damaged (records follow).
      hal::StorageStatus s = hal::StorageStatus::kOk;
      const bool rest_erased = range_erased(storage, hstride, g.sector_bytes, &s);
      if (s != hal::StorageStatus::kOk) return storage_error(s);
      scan.status = rest_erased ? JournalStatus::kTornHeader : JournalStatus::kCorruptHeader;
    }
    return scan;
  }
  const Header& hd = scan.header;
  const int dim = hd.identity.outcome_dim;
  if (hd.write_block != g.write_block_bytes || hd.header_stride != header_stride_for(g, hd.version) ||
      hd.record_stride != record_stride_for(g, dim)) {
    scan.bad_reason = DecodeResult::kBadLayout;
    scan.status = JournalStatus::kCorruptHeader;
    return scan;
  }
  const uint32_t stride = hd.record_stride;
  scan.slots = (g.size_bytes - hd.header_stride) / stride;

  bool pending = false;  // a run of invalid slots [torn_first, i) not yet explained
  uint32_t first_bad = 0;
  DecodeResult first_reason = DecodeResult::kOk;
  auto corrupt = [&](uint32_t slot, DecodeResult why) {
    scan.status = JournalStatus::kCorrupt;
    scan.bad_slot = slot;
    scan.bad_reason = why;
    return scan;
  };
  uint32_t i = 0;
  for (; i < scan.slots; ++i) {
    if (const hal::StorageStatus s = storage.read(hd.header_stride + i * stride, buf, stride);
        s != hal::StorageStatus::kOk)
      return storage_error(s);
    Record rec;
    const DecodeResult d = decode_record(buf, stride, dim, hd.crc, &rec);
    if (d == DecodeResult::kErased) break;
    // A record that validates cannot come from a torn write: one out of place (another slot's
    // number, an episode out of sequence) is corruption, as is any damage before it. (Counting
    // it as invalid instead made a bad slot mid-journal swallow every record after it as a
    // "torn tail".)
    if (d == DecodeResult::kOk &&
        (rec.slot != i || (rec.type == RecordType::kEpisode && rec.entry.episode != scan.episodes)))
      return pending ? corrupt(first_bad, first_reason) : corrupt(i, DecodeResult::kBadLayout);
    if (d != DecodeResult::kOk) {
      if (!pending) {
        pending = true;
        first_bad = i;
        first_reason = d;
      }
      continue;
    }
    if (rec.type == RecordType::kSkip) {
      // Acknowledges exactly the invalid run before it, nothing else.
      if (!pending || rec.skipped_slot != first_bad)
        return corrupt(pending ? first_bad : i, DecodeResult::kBadLayout);
      scan.acknowledged_slots += i - first_bad;
      pending = false;
      scan.last_valid_slot = i + 1;
      continue;
    }
    if (pending) return corrupt(first_bad, first_reason);  // damage before good records
    ++scan.episodes;
    scan.last_valid_slot = i + 1;
  }
  // Everything after the end must be erased: a write only ever goes to the first free slot.
  if (i < scan.slots) {
    hal::StorageStatus s = hal::StorageStatus::kOk;
    if (!range_erased(storage, hd.header_stride + (i + 1) * stride, g.size_bytes, &s)) {
      if (s != hal::StorageStatus::kOk) return storage_error(s);
      return corrupt(pending ? first_bad : i, pending ? first_reason : DecodeResult::kErased);
    }
  }
  if (pending) {
    scan.torn_tail = true;
    scan.torn_first = first_bad;
    scan.torn_slots = i - first_bad;
    scan.torn_reason = first_reason;
  }
  scan.next_slot = i;
  scan.status = JournalStatus::kOk;
  return scan;
}

JournalStatus JournalReader::open(hal::Storage* storage, const JournalScan& scan) {
  storage_ = nullptr;
  if (storage == nullptr || scan.status != JournalStatus::kOk)
    return JournalStatus::kInvalidArgument;
  storage_ = storage;
  scan_ = scan;
  slot_ = 0;
  episodes_read_ = 0;
  return JournalStatus::kOk;
}

JournalStatus JournalReader::next(EpisodeEntry* entry, bool* end) {
  if (storage_ == nullptr) return JournalStatus::kNotOpen;
  if (entry == nullptr || end == nullptr) return JournalStatus::kInvalidArgument;
  *end = false;
  const Header& h = scan_.header;
  uint8_t buf[kMaxBlockBytes];
  while (episodes_read_ < scan_.episodes) {
    if (slot_ >= scan_.next_slot) return JournalStatus::kCorrupt;  // changed since the scan
    const uint32_t slot = slot_++;
    if (const hal::StorageStatus s =
            storage_->read(h.header_stride + slot * h.record_stride, buf, h.record_stride);
        s != hal::StorageStatus::kOk)
      return JournalStatus::kStorageError;
    Record rec;
    // Invalid slots here are the ones the scan found acknowledged by a skip record.
    if (decode_record(buf, h.record_stride, h.identity.outcome_dim, h.crc, &rec) !=
            DecodeResult::kOk ||
        rec.type != RecordType::kEpisode)
      continue;
    if (rec.entry.episode != episodes_read_) return JournalStatus::kCorrupt;
    ++episodes_read_;
    *entry = rec.entry;
    return JournalStatus::kOk;
  }
  *end = true;
  return JournalStatus::kOk;
}

JournalStatus JournalWriter::create(hal::Storage* storage, const RunIdentity& identity,
                                    uint32_t sync_every) {
  storage_ = nullptr;
  if (storage == nullptr) return fail(JournalStatus::kInvalidArgument);
  const hal::StorageGeometry& g = storage->geometry();
  const uint16_t version = has_strategy(identity) ? kVersion : kVersionSpec;
  const uint32_t hstride = header_stride_for(g, version);
  const uint32_t rstride = record_stride_for(g, identity.outcome_dim);
  if (hstride == 0 || rstride == 0 || slot_capacity(g, identity.outcome_dim, version) == 0)
    return fail(JournalStatus::kInvalidArgument);
  // The old header first: from here on no old run validates, whatever a cut leaves.
  storage_status_ = storage->erase(0, g.sector_bytes);
  if (storage_status_ == hal::StorageStatus::kOk && g.size_bytes > g.sector_bytes)
    storage_status_ = storage->erase(g.sector_bytes, g.size_bytes - g.sector_bytes);
  if (storage_status_ != hal::StorageStatus::kOk) return fail(JournalStatus::kStorageError);
  uint8_t buf[kMaxBlockBytes] = {};
  encode_header(identity, static_cast<uint16_t>(hstride), static_cast<uint16_t>(rstride),
                static_cast<uint16_t>(g.write_block_bytes), buf);
  storage_status_ = storage->write(0, buf, hstride);
  if (storage_status_ == hal::StorageStatus::kOk) storage_status_ = storage->sync();
  if (storage_status_ != hal::StorageStatus::kOk) return fail(JournalStatus::kStorageError);
  ++counters_.syncs;
  if (decode_header(buf, hstride, &header_) != DecodeResult::kOk)
    return fail(JournalStatus::kInvalidArgument);
  storage_ = storage;
  slots_ = slot_capacity(g, identity.outcome_dim, version);
  slot_ = 0;
  episodes_ = 0;
  sync_every_ = sync_every;
  unsynced_ = 0;
  return JournalStatus::kOk;
}

JournalStatus JournalWriter::resume(hal::Storage* storage, const JournalScan& scan,
                                    uint32_t sync_every) {
  storage_ = nullptr;
  if (storage == nullptr || scan.status != JournalStatus::kOk)
    return fail(JournalStatus::kInvalidArgument);
  header_ = scan.header;
  slots_ = scan.slots;
  slot_ = scan.next_slot;
  episodes_ = scan.episodes;
  sync_every_ = sync_every;
  unsynced_ = 0;
  storage_ = storage;
  if (scan.torn_tail) {
    Record skip;
    skip.type = RecordType::kSkip;
    skip.slot = slot_;
    skip.skipped_slot = scan.torn_first;
    const JournalStatus s = write_slot(skip);
    if (s == JournalStatus::kOk) storage_status_ = storage_->sync();
    if (s != JournalStatus::kOk || storage_status_ != hal::StorageStatus::kOk) {
      storage_ = nullptr;
      return s != JournalStatus::kOk ? s : fail(JournalStatus::kStorageError);
    }
    ++counters_.skips_written;
    ++counters_.syncs;
    ++slot_;
  }
  return JournalStatus::kOk;
}

JournalStatus JournalWriter::write_slot(const Record& r) {
  if (slot_ >= slots_) return fail(JournalStatus::kFull);
  uint8_t buf[kMaxBlockBytes] = {};
  encode_record(r, header_.identity.outcome_dim, header_.crc, buf);
  storage_status_ = storage_->write(header_.header_stride + slot_ * header_.record_stride, buf,
                                    header_.record_stride);
  if (storage_status_ != hal::StorageStatus::kOk) return fail(JournalStatus::kStorageError);
  return JournalStatus::kOk;
}

JournalStatus JournalWriter::append(const EpisodeEntry& entry) {
  if (storage_ == nullptr) return fail(JournalStatus::kNotOpen);
  if (entry.episode != episodes_) return fail(JournalStatus::kWrongEpisode);
  if (entry.outcome_dim != header_.identity.outcome_dim)
    return fail(JournalStatus::kInvalidArgument);
  Record r;
  r.type = RecordType::kEpisode;
  r.slot = slot_;
  r.entry = entry;
  if (const JournalStatus s = write_slot(r); s != JournalStatus::kOk) return s;
  ++slot_;
  ++episodes_;
  ++counters_.appends;
  if (sync_every_ > 0 && ++unsynced_ >= sync_every_) return sync();
  return JournalStatus::kOk;
}

JournalStatus JournalWriter::sync() {
  if (storage_ == nullptr) return fail(JournalStatus::kNotOpen);
  storage_status_ = storage_->sync();
  if (storage_status_ != hal::StorageStatus::kOk) return fail(JournalStatus::kStorageError);
  ++counters_.syncs;
  unsynced_ = 0;
  return JournalStatus::kOk;
}

}  // namespace curio::journal
