// Byte-level codecs of the journal format (firmware/journal/journal_format.hpp).
#include "firmware/journal/journal_format.hpp"

#include <cstring>

#include "firmware/journal/crc32.hpp"

namespace curio::journal {

namespace {

constexpr uint8_t kHeaderMagic[8] = {'C', 'U', 'R', 'I', 'O', 'J', 'N', 'L'};

// Little-endian cursor over a fixed buffer.
struct Put {
  uint8_t* p;
  void u8(uint8_t v) { *p++ = v; }
  void u16(uint16_t v) {
    u8(static_cast<uint8_t>(v));
    u8(static_cast<uint8_t>(v >> 8));
  }
  void u32(uint32_t v) {
    for (int i = 0; i < 4; ++i) u8(static_cast<uint8_t>(v >> (8 * i)));
  }
  void u64(uint64_t v) {
    u32(static_cast<uint32_t>(v));
    u32(static_cast<uint32_t>(v >> 32));
  }
  void f32(float f) {
    uint32_t v;
    std::memcpy(&v, &f, 4);
    u32(v);
  }
  void bytes(const void* src, size_t n) {
    std::memcpy(p, src, n);
    p += n;
  }
};

struct Get {
  const uint8_t* p;
  uint8_t u8() { return *p++; }
  uint16_t u16() {
    const uint16_t lo = u8();
    return static_cast<uint16_t>(lo | (uint16_t{u8()} << 8));
  }
  uint32_t u32() {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= uint32_t{u8()} << (8 * i);
    return v;
  }
  uint64_t u64() {
    const uint64_t lo = u32();
    return lo | (uint64_t{u32()} << 32);
  }
  float f32() {
    const uint32_t v = u32();
    float f;
    std::memcpy(&f, &v, 4);
    return f;
  }
  void bytes(void* dst, size_t n) {
    std::memcpy(dst, p, n);
    p += n;
  }
};

bool all_erased(const uint8_t* in, size_t len) {
  for (size_t i = 0; i < len; ++i)
    if (in[i] != 0xFF) return false;
  return true;
}

uint32_t bits(float f) {
  uint32_t v;
  std::memcpy(&v, &f, 4);
  return v;
}

}  // namespace

const char* to_string(IdentityField f) {
  switch (f) {
    case IdentityField::kNone:
      return "none";
    case IdentityField::kAlgorithmName:
      return "algorithm";
    case IdentityField::kAlgorithm:
      return "algorithm kind";
    case IdentityField::kSeed:
      return "seed";
    case IdentityField::kSigma:
      return "sigma";
    case IdentityField::kBootstrap:
      return "bootstrap";
    case IdentityField::kEpisodes:
      return "episodes";
    case IdentityField::kCompetenceCap:
      return "competence clip";
    case IdentityField::kCompetenceMeasure:
      return "competence measure";
    case IdentityField::kWindow:
      return "interest window";
    case IdentityField::kEpsilon:
      return "epsilon";
    case IdentityField::kGoalBound:
      return "goal bound";
    case IdentityField::kGoalKind:
      return "goal kind";
    case IdentityField::kOutcomeDim:
      return "outcome dimension";
    case IdentityField::kModules:
      return "modules";
    case IdentityField::kTieRule:
      return "tie rule";
    case IdentityField::kRequeryExploit:
      return "exploit re-query";
    case IdentityField::kPhysics:
      return "physics";
    case IdentityField::kWeights:
      return "encoder weights";
    case IdentityField::kEnvironment:
      return "world hash";
    case IdentityField::kStrategy:
      return "explore strategy";
  }
  return "unknown";
}

IdentityField first_difference(const RunIdentity& a, const RunIdentity& b) {
  if (std::memcmp(a.algorithm_name, b.algorithm_name, kAlgorithmNameBytes) != 0)
    return IdentityField::kAlgorithmName;
  if (a.algorithm != b.algorithm) return IdentityField::kAlgorithm;
  if (a.seed != b.seed) return IdentityField::kSeed;
  if (bits(a.sigma) != bits(b.sigma)) return IdentityField::kSigma;
  if (a.n_bootstrap != b.n_bootstrap) return IdentityField::kBootstrap;
  if (a.n_episodes != b.n_episodes) return IdentityField::kEpisodes;
  if (bits(a.competence_cap) != bits(b.competence_cap)) return IdentityField::kCompetenceCap;
  if (a.competence_measure != b.competence_measure) return IdentityField::kCompetenceMeasure;
  if (bits(a.window) != bits(b.window)) return IdentityField::kWindow;
  if (bits(a.epsilon) != bits(b.epsilon)) return IdentityField::kEpsilon;
  if (bits(a.goal_bound) != bits(b.goal_bound)) return IdentityField::kGoalBound;
  if (a.goal_kind != b.goal_kind) return IdentityField::kGoalKind;
  if (a.outcome_dim != b.outcome_dim) return IdentityField::kOutcomeDim;
  if (a.n_modules != b.n_modules || a.modules_hash != b.modules_hash)
    return IdentityField::kModules;
  if (a.tie_rule != b.tie_rule) return IdentityField::kTieRule;
  if (a.requery_exploit != b.requery_exploit) return IdentityField::kRequeryExploit;
  if (a.physics != b.physics) return IdentityField::kPhysics;
  if (a.weights_hash != b.weights_hash) return IdentityField::kWeights;
  if (a.environment_hash != b.environment_hash) return IdentityField::kEnvironment;
  if (bits(a.frontier_share) != bits(b.frontier_share)) return IdentityField::kStrategy;
  for (int i = 0; i < kExploreEpisodesPerStep; ++i)
    if (bits(a.sigma_ladder[i]) != bits(b.sigma_ladder[i])) return IdentityField::kStrategy;
  return IdentityField::kNone;
}

bool has_strategy(const RunIdentity& id) {
  if (bits(id.frontier_share) != 0) return true;
  for (int i = 0; i < kExploreEpisodesPerStep; ++i)
    if (bits(id.sigma_ladder[i]) != 0) return true;
  return false;
}

const char* to_string(DecodeResult r) {
  switch (r) {
    case DecodeResult::kOk:
      return "ok";
    case DecodeResult::kErased:
      return "erased";
    case DecodeResult::kBadMagic:
      return "bad magic";
    case DecodeResult::kBadCrc:
      return "CRC mismatch";
    case DecodeResult::kBadVersion:
      return "unsupported version";
    case DecodeResult::kBadLayout:
      return "bad layout";
  }
  return "unknown";
}

void encode_identity(const RunIdentity& id, uint8_t out[kIdentityBytes]) {
  Put w{out};
  w.u64(id.seed);
  w.u32(id.n_bootstrap);
  w.u32(id.n_episodes);
  w.f32(id.sigma);
  w.f32(id.competence_cap);
  w.f32(id.window);
  w.f32(id.epsilon);
  w.f32(id.goal_bound);
  w.u8(id.algorithm);
  w.u8(id.outcome_dim);
  w.u8(id.n_modules);
  w.u8(id.goal_kind);
  w.u8(id.competence_measure);
  w.u8(id.tie_rule);
  w.u8(id.requery_exploit);
  w.u8(id.physics);
  w.u32(id.modules_hash);
  w.u32(id.weights_hash);
  w.u32(id.environment_hash);
  w.bytes(id.algorithm_name, kAlgorithmNameBytes);
}

void decode_identity(const uint8_t in[kIdentityBytes], RunIdentity* id) {
  Get r{in};
  id->seed = r.u64();
  id->n_bootstrap = r.u32();
  id->n_episodes = r.u32();
  id->sigma = r.f32();
  id->competence_cap = r.f32();
  id->window = r.f32();
  id->epsilon = r.f32();
  id->goal_bound = r.f32();
  id->algorithm = r.u8();
  id->outcome_dim = r.u8();
  id->n_modules = r.u8();
  id->goal_kind = r.u8();
  id->competence_measure = r.u8();
  id->tie_rule = r.u8();
  id->requery_exploit = r.u8();
  id->physics = r.u8();
  id->modules_hash = r.u32();
  id->weights_hash = r.u32();
  id->environment_hash = r.u32();
  r.bytes(id->algorithm_name, kAlgorithmNameBytes);
  id->algorithm_name[kAlgorithmNameBytes - 1] = '\0';
}
// 8+4+4+5·4+8+3·4+24 = 80 bytes.
static_assert(kIdentityBytes == 8 + 4 + 4 + 5 * 4 + 8 + 3 * 4 + kAlgorithmNameBytes);

size_t encode_header(const RunIdentity& id, uint16_t header_stride, uint16_t record_stride,
                     uint16_t write_block, uint8_t out[kHeaderBytes]) {
  const uint16_t version = has_strategy(id) ? kVersion : kVersionSpec;
  const size_t n = header_bytes(version);
  Put w{out};
  w.bytes(kHeaderMagic, 8);
  w.u16(version);
  w.u16(header_stride);
  w.u16(record_stride);
  w.u16(write_block);
  encode_identity(id, w.p);
  w.p += kIdentityBytes;
  if (version == kVersion) {
    w.f32(id.frontier_share);
    for (int i = 0; i < kExploreEpisodesPerStep; ++i) w.f32(id.sigma_ladder[i]);
  }
  w.u32(crc32(out, n - 4));
  return n;
}

DecodeResult decode_header(const uint8_t* in, size_t len, Header* h) {
  if (len < kHeaderBytesV1) return DecodeResult::kBadLayout;
  if (all_erased(in, kHeaderBytesV1)) return DecodeResult::kErased;
  if (std::memcmp(in, kHeaderMagic, 8) != 0) return DecodeResult::kBadMagic;
  Get r{in + 8};
  h->version = r.u16();
  h->header_stride = r.u16();
  h->record_stride = r.u16();
  h->write_block = r.u16();
  const size_t n = header_bytes(h->version);
  if (n == 0) {
    // A version this build does not know, or a damaged version field: the CRC of either
    // known layout tells which.
    const size_t known_sizes[] = {kHeaderBytesV1, kHeaderBytes};
    for (const size_t known : known_sizes)
      if (len >= known && crc32(in, known - 4) == Get{in + known - 4}.u32())
        return DecodeResult::kBadVersion;
    return DecodeResult::kBadCrc;
  }
  if (len < n) return DecodeResult::kBadLayout;
  h->crc = Get{in + n - 4}.u32();
  if (crc32(in, n - 4) != h->crc) return DecodeResult::kBadCrc;
  decode_identity(in + 16, &h->identity);
  Get strategy{in + 16 + kIdentityBytes};
  h->identity.frontier_share = h->version == kVersion ? strategy.f32() : 0.0f;
  for (int i = 0; i < kExploreEpisodesPerStep; ++i)
    h->identity.sigma_ladder[i] = h->version == kVersion ? strategy.f32() : 0.0f;
  // A version 2 header naming SPEC's strategy is not one this format writes.
  if (h->version == kVersion && !has_strategy(h->identity)) return DecodeResult::kBadLayout;
  const int dim = h->identity.outcome_dim;
  if (dim < 1 || dim > kMaxOutcomeDim || h->write_block == 0 ||
      h->header_stride < n || h->header_stride % h->write_block != 0 ||
      h->record_stride < record_bytes(dim) || h->record_stride % h->write_block != 0 ||
      h->record_stride > kMaxBlockBytes || h->header_stride > kMaxBlockBytes)
    return DecodeResult::kBadLayout;
  return DecodeResult::kOk;
}

size_t encode_record(const Record& rec, int outcome_dim, uint32_t nonce,
                     uint8_t out[kMaxRecordBytes]) {
  const EpisodeEntry& e = rec.entry;
  const bool episode = rec.type == RecordType::kEpisode;
  Put w{out};
  w.u32(kRecordMagic);
  w.u8(static_cast<uint8_t>(rec.type));
  w.u8(static_cast<uint8_t>(outcome_dim));
  w.u8(episode ? static_cast<uint8_t>((e.grasped ? 1 : 0) | (e.exploit ? 2 : 0)) : 0);
  w.u8(episode ? static_cast<uint8_t>(e.module) : 0);
  w.u32(rec.slot);
  w.u32(episode ? e.episode : rec.skipped_slot);
  w.u8(episode ? e.kind : 0);
  w.u8(episode ? e.attempts : 0);
  w.u16(0);
  const EpisodeEntry zero;
  const EpisodeEntry& v = episode ? e : zero;
  w.f32(v.ball[0]);
  w.f32(v.ball[1]);
  w.f32(v.distractor[0]);
  w.f32(v.distractor[1]);
  w.f32(v.progress);
  for (int i = 0; i < outcome_dim; ++i) w.f32(v.outcome[i]);
  const size_t body = static_cast<size_t>(w.p - out);
  uint8_t n[4];
  Put{n}.u32(nonce);
  w.u32(crc32_final(crc32_update(crc32_update(kCrc32Init, n, 4), out, body)));
  return body + 4;
}

DecodeResult decode_record(const uint8_t* in, size_t len, int outcome_dim, uint32_t nonce,
                           Record* rec) {
  if (outcome_dim < 1 || outcome_dim > kMaxOutcomeDim || len < record_bytes(outcome_dim))
    return DecodeResult::kBadLayout;
  if (all_erased(in, len)) return DecodeResult::kErased;
  Get r{in};
  if (r.u32() != kRecordMagic) return DecodeResult::kBadMagic;
  const size_t body = record_bytes(outcome_dim) - 4;
  uint8_t n[4];
  Put{n}.u32(nonce);
  const uint32_t crc = crc32_final(crc32_update(crc32_update(kCrc32Init, n, 4), in, body));
  Get c{in + body};
  if (c.u32() != crc) return DecodeResult::kBadCrc;
  const uint8_t type = r.u8();
  if (type != static_cast<uint8_t>(RecordType::kEpisode) &&
      type != static_cast<uint8_t>(RecordType::kSkip))
    return DecodeResult::kBadLayout;
  if (r.u8() != outcome_dim) return DecodeResult::kBadLayout;
  rec->type = static_cast<RecordType>(type);
  EpisodeEntry& e = rec->entry;
  e = EpisodeEntry{};
  const uint8_t flags = r.u8();
  e.grasped = (flags & 1) != 0;
  e.exploit = (flags & 2) != 0;
  e.module = static_cast<int8_t>(r.u8());
  rec->slot = r.u32();
  const uint32_t episode = r.u32();
  e.kind = r.u8();
  e.attempts = r.u8();
  r.u16();
  e.ball[0] = r.f32();
  e.ball[1] = r.f32();
  e.distractor[0] = r.f32();
  e.distractor[1] = r.f32();
  e.progress = r.f32();
  e.outcome_dim = static_cast<uint8_t>(outcome_dim);
  for (int i = 0; i < outcome_dim; ++i) e.outcome[i] = r.f32();
  if (rec->type == RecordType::kEpisode) {
    e.episode = episode;
    rec->skipped_slot = 0;
  } else {
    rec->skipped_slot = episode;
  }
  // Padding up to the slot: zeros (anything else is damage).
  for (size_t i = record_bytes(outcome_dim); i < len; ++i)
    if (in[i] != 0) return DecodeResult::kBadLayout;
  return DecodeResult::kOk;
}

}  // namespace curio::journal
