// libFuzzer target: the journal's decoders and scan (firmware/journal) on arbitrary flash
// content, and on valid journals with arbitrary damage. Oracles beyond "no crash, no UB":
//   - a decoded header or record re-encodes to bytes that decode to the same values;
//   - a scan's figures are consistent (episodes ≤ slots, torn run inside [0, next_slot), the
//     reader yields exactly scan.episodes entries numbered 0, 1, ...);
//   - a journal the scan calls kOk can be resumed and appended to, and the next scan finds
//     every earlier episode plus the new ones (recovery never loses what the scan kept);
//   - anything else (kCorrupt, a bad header, ...) makes resume refuse, and the flash is left
//     exactly as it was;
//   - damage to a valid journal never loses records before the first damaged byte, and is
//     never reported before it.
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "firmware/journal/journal.hpp"
#include "hal/sim_flash.hpp"
#include "tests/fuzz/fuzz_check.hpp"

using namespace curio;
using namespace curio::journal;

namespace {

constexpr uint32_t kWordChoices[] = {8, 16, 32, 64};
constexpr uint32_t kSector = 256;
constexpr uint32_t kFlash = 4 * kSector;

bool same(const EpisodeEntry& a, const EpisodeEntry& b) {
  return a.episode == b.episode && a.kind == b.kind && a.module == b.module &&
         a.exploit == b.exploit && a.grasped == b.grasped && a.attempts == b.attempts &&
         a.outcome_dim == b.outcome_dim && std::memcmp(a.ball, b.ball, sizeof a.ball) == 0 &&
         std::memcmp(a.distractor, b.distractor, sizeof a.distractor) == 0 &&
         std::memcmp(&a.progress, &b.progress, 4) == 0 &&
         std::memcmp(a.outcome, b.outcome, 4 * static_cast<size_t>(a.outcome_dim)) == 0;
}

// Decoders alone: whatever decodes re-encodes to something that decodes to the same.
void fuzz_decoders(const uint8_t* data, size_t size) {
  if (size < 6) return;
  const int dim = 1 + data[0] % kMaxOutcomeDim;
  uint32_t nonce;
  std::memcpy(&nonce, data + 1, 4);
  const uint8_t* p = data + 5;
  const size_t n = size - 5;
  Record r;
  if (decode_record(p, n, dim, nonce, &r) == DecodeResult::kOk) {
    check(r.entry.outcome_dim == dim);
    uint8_t buf[kMaxRecordBytes];
    const size_t len = encode_record(r, dim, nonce, buf);
    check(len == record_bytes(dim));
    Record back;
    check(decode_record(buf, len, dim, nonce, &back) == DecodeResult::kOk);
    check(back.type == r.type && back.slot == r.slot);
    if (r.type == RecordType::kEpisode) check(same(back.entry, r.entry));
    if (r.type == RecordType::kSkip) check(back.skipped_slot == r.skipped_slot);
    // The same bytes under another run's nonce never validate (a CRC is over the nonce).
    check(decode_record(buf, len, dim, nonce ^ 1u, &back) == DecodeResult::kBadCrc);
  }
  Header h;
  if (decode_header(p, n, &h) == DecodeResult::kOk) {
    uint8_t buf[kHeaderBytes];
    encode_header(h.identity, h.header_stride, h.record_stride, h.write_block, buf);
    Header back;
    check(decode_header(buf, kHeaderBytes, &back) == DecodeResult::kOk);
    check(first_difference(back.identity, h.identity) == IdentityField::kNone);
    check(back.record_stride == h.record_stride && back.header_stride == h.header_stride);
  }
}

struct Scanned {
  JournalScan scan;
  std::vector<EpisodeEntry> entries;
};

Scanned scan_and_read(hal::Storage& flash) {
  Scanned s;
  s.scan = scan_journal(flash);
  const JournalScan& sc = s.scan;
  check(sc.status != JournalStatus::kStorageError);
  if (sc.status != JournalStatus::kOk) return s;
  check(sc.episodes <= sc.slots && sc.next_slot <= sc.slots);
  check(sc.last_valid_slot <= sc.next_slot);
  check(sc.episodes + sc.acknowledged_slots <= sc.next_slot);
  if (sc.torn_tail) {
    check(sc.torn_slots > 0 && sc.torn_first + sc.torn_slots == sc.next_slot);
    check(sc.torn_first == sc.last_valid_slot);
  } else {
    check(sc.last_valid_slot == sc.next_slot);
  }
  JournalReader reader;
  check(reader.open(&flash, sc) == JournalStatus::kOk);
  for (;;) {
    EpisodeEntry e;
    bool end = false;
    check(reader.next(&e, &end) == JournalStatus::kOk);
    if (end) break;
    check(e.episode == s.entries.size());
    s.entries.push_back(e);
  }
  check(s.entries.size() == sc.episodes);
  return s;
}

EpisodeEntry make_entry(FuzzedDataProvider& in, uint32_t episode, int dim) {
  EpisodeEntry e;
  e.episode = episode;
  e.kind = in.ConsumeIntegral<uint8_t>();
  e.module = in.ConsumeIntegral<int8_t>();
  e.exploit = in.ConsumeBool();
  e.grasped = in.ConsumeBool();
  e.attempts = in.ConsumeIntegral<uint8_t>();
  e.outcome_dim = static_cast<uint8_t>(dim);
  auto f = [&] {
    const uint32_t v = in.ConsumeIntegral<uint32_t>();
    float x;
    std::memcpy(&x, &v, 4);
    return x;
  };
  e.ball[0] = f();
  e.ball[1] = f();
  e.distractor[0] = f();
  e.distractor[1] = f();
  e.progress = f();
  for (int d = 0; d < dim; ++d) e.outcome[d] = f();
  return e;
}

// What the scan found must survive a resume and appends; what it refused must stay untouched.
void check_recovery(FuzzedDataProvider& in, std::vector<uint8_t>& mem, uint32_t word,
                    const Scanned& before) {
  hal::SimFlash flash(mem.data(), kFlash, kSector, word);
  JournalWriter w;
  if (before.scan.status != JournalStatus::kOk) {
    const std::vector<uint8_t> copy = mem;
    check(w.resume(&flash, before.scan) == JournalStatus::kInvalidArgument);
    check(w.append(EpisodeEntry{}) == JournalStatus::kNotOpen);
    check(mem == copy);
    return;
  }
  const JournalStatus rs = w.resume(&flash, before.scan);
  if (rs == JournalStatus::kFull) return;  // no slot for the skip record
  check(rs == JournalStatus::kOk);
  const int dim = before.scan.header.identity.outcome_dim;
  uint32_t appended = 0;
  const uint32_t want = in.ConsumeIntegralInRange<uint32_t>(0, 3);
  for (uint32_t i = 0; i < want; ++i) {
    const JournalStatus s = w.append(make_entry(in, before.scan.episodes + i, dim));
    if (s == JournalStatus::kFull) break;
    check(s == JournalStatus::kOk);
    ++appended;
  }
  hal::SimFlash again(mem.data(), kFlash, kSector, word);
  const Scanned after = scan_and_read(again);
  check(after.scan.status == JournalStatus::kOk);
  check(!after.scan.torn_tail);
  check(after.scan.episodes == before.scan.episodes + appended);
  for (size_t i = 0; i < before.entries.size(); ++i)
    check(same(after.entries[i], before.entries[i]));
}

// Raw bytes as flash content (then erased).
void fuzz_raw_flash(FuzzedDataProvider& in) {
  const uint32_t word = kWordChoices[in.ConsumeIntegralInRange<int>(0, 3)];
  std::vector<uint8_t> mem(kFlash, 0xFF);
  const std::vector<uint8_t> bytes =
      in.ConsumeBytes<uint8_t>(in.ConsumeIntegralInRange<size_t>(0, kFlash));
  std::copy(bytes.begin(), bytes.end(), mem.begin());
  hal::SimFlash flash(mem.data(), kFlash, kSector, word);
  const Scanned s = scan_and_read(flash);
  check_recovery(in, mem, word, s);
}

// A valid journal, then damage: bit flips, bits cleared (what flash can do by itself), bytes
// erased back to 0xFF, a torn append.
void fuzz_damaged_journal(FuzzedDataProvider& in) {
  const uint32_t word = kWordChoices[in.ConsumeIntegralInRange<int>(0, 3)];
  std::vector<uint8_t> mem(kFlash, 0xFF);
  hal::SimFlash flash(mem.data(), kFlash, kSector, word);
  RunIdentity id;
  id.seed = in.ConsumeIntegral<uint64_t>();
  id.outcome_dim = static_cast<uint8_t>(in.ConsumeIntegralInRange<int>(1, kMaxOutcomeDim));
  id.algorithm = in.ConsumeIntegral<uint8_t>();
  id.sigma = 0.05f;
  JournalWriter w;
  check(w.create(&flash, id) == JournalStatus::kOk);
  const uint32_t n = in.ConsumeIntegralInRange<uint32_t>(0, w.slots());
  std::vector<EpisodeEntry> written;
  for (uint32_t i = 0; i < n; ++i) {
    written.push_back(make_entry(in, i, id.outcome_dim));
    check(w.append(written.back()) == JournalStatus::kOk);
  }
  bool torn = false;
  EpisodeEntry torn_entry;
  if (in.ConsumeBool() && n < w.slots()) {  // a torn append
    torn = true;
    torn_entry = make_entry(in, n, id.outcome_dim);
    flash.power_cut_after(in.ConsumeIntegralInRange<uint32_t>(0, w.record_stride() - 1));
    check(w.append(torn_entry) == JournalStatus::kStorageError);
    flash.power_on();
  }
  const std::vector<uint8_t> clean = mem;
  const int damages = in.ConsumeIntegralInRange<int>(0, 4);
  for (int d = 0; d < damages; ++d) {
    const uint32_t at = in.ConsumeIntegralInRange<uint32_t>(0, kFlash - 1);
    const uint8_t v = in.ConsumeIntegral<uint8_t>();
    switch (in.ConsumeIntegralInRange<int>(0, 2)) {
      case 0:
        mem[at] ^= v;
        break;
      case 1:
        mem[at] &= v;
        break;
      default: {
        const uint32_t len = in.ConsumeIntegralInRange<uint32_t>(1, 64);
        for (uint32_t i = at; i < at + len && i < kFlash; ++i) mem[i] = 0xFF;
      }
    }
  }
  uint32_t first_changed = kFlash;
  for (uint32_t i = 0; i < kFlash; ++i)
    if (mem[i] != clean[i]) {
      first_changed = i;
      break;
    }
  hal::SimFlash damaged(mem.data(), kFlash, kSector, word);
  const Scanned s = scan_and_read(damaged);
  if (first_changed >= w.header_stride()) {
    // The header intact: records before the first damaged slot are all kept.
    const uint32_t intact_slots = (first_changed - w.header_stride()) / w.record_stride();
    const uint32_t intact = intact_slots < n ? intact_slots : n;
    check(s.scan.status == JournalStatus::kOk || s.scan.status == JournalStatus::kCorrupt);
    check(s.scan.episodes >= intact);
    if (s.scan.status == JournalStatus::kCorrupt) check(s.scan.bad_slot >= intact);
    for (uint32_t i = 0; i < intact && i < s.entries.size(); ++i)
      check(same(s.entries[i], written[i]));
    // Undamaged: all n records; n + 1 when the torn append's unwritten bytes all happened to
    // be 0xFF already (its record is then complete, bit for bit).
    if (first_changed == kFlash) {
      check(s.scan.status == JournalStatus::kOk);
      check(s.scan.episodes == n ||
            (torn && s.scan.episodes == n + 1 && same(s.entries[n], torn_entry)));
    }
  }
  check_recovery(in, mem, word, s);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  switch (data[0] % 3) {
    case 0:
      fuzz_decoders(data + 1, size - 1);
      break;
    case 1: {
      FuzzedDataProvider in(data + 1, size - 1);
      fuzz_raw_flash(in);
      break;
    }
    default: {
      FuzzedDataProvider in(data + 1, size - 1);
      fuzz_damaged_journal(in);
    }
  }
  return 0;
}
