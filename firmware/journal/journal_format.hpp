// The exploration journal's on-storage format (versions 1 and 2): one header block naming the
// run, then one fixed-stride slot per record. All integers little-endian, floats as their
// IEEE-754 bit patterns, whatever the machine; every block padded with zeros to a multiple of
// the storage's write block (32 bytes on an STM32H7) so no two records share a flash word.
//
//   header (header_bytes(version): 100 for version 1, 120 for version 2; padded):
//     0  "CURIOJNL"            8  u16 version   10 u16 header_stride   12 u16 record_stride
//     14 u16 write_block       16 RunIdentity (80 bytes, encode_identity)
//     version 1: 96 u32 CRC-32 of 0..95
//     version 2: 96 f32 frontier_share  100 f32 sigma_ladder[4]  116 u32 CRC-32 of 0..115
//   A run whose explore strategy is SPEC's (frontier_share 0, no σ ladder) is written as
//   version 1, byte for byte what every journal was before strategies were named, so those
//   journals resume and their checksums hold; any other strategy is written as version 2.
//   record slot i (record_stride = round_up(kRecordFixedBytes + 4·outcome_dim + 4, write_block)),
//   at header_stride + i·record_stride:
//     0  u32 magic 'CJR1'      4  u8 type (1 episode, 2 skip)   5 u8 outcome_dim
//     6  u8 flags (1 grasped, 2 exploit)   7 i8 module   8 u32 slot (= i)
//     12 u32 episode (type 1: the archive index; type 2: the slot it skips)
//     16 u8 kind   17 u8 attempts   18 u16 0   20 f32 ball x, y   28 f32 distractor x, y
//     36 f32 progress   40 f32 outcome[outcome_dim]
//     40+4d u32 CRC-32 of the header's CRC (4 bytes, the run's nonce) then bytes 0 .. 40+4d−1
// A slot reading all 0xFF is erased (the journal ends there). The nonce in every record's CRC
// means a record can never validate under another run's header.
#pragma once
#include <cstddef>
#include <cstdint>

#include "firmware/explore/config.hpp"
#include "firmware/explore/schedule.hpp"

namespace curio::journal {

inline constexpr uint16_t kVersion = 2;      // the newest version this build writes and reads
inline constexpr uint16_t kVersionSpec = 1;  // written for SPEC's explore strategy
inline constexpr uint32_t kRecordMagic = 0x31524A43u;  // "CJR1"
inline constexpr size_t kIdentityBytes = 80;
inline constexpr size_t kStrategyBytes = 4 + 4 * static_cast<size_t>(kExploreEpisodesPerStep);  // version 2 only
inline constexpr size_t kHeaderBytesV1 = 16 + kIdentityBytes + 4;
inline constexpr size_t kHeaderBytes = 16 + kIdentityBytes + kStrategyBytes + 4;  // the largest
// A header's size by its version (0: a version this build does not know).
constexpr size_t header_bytes(uint16_t version) {
  return version == kVersionSpec ? kHeaderBytesV1 : version == kVersion ? kHeaderBytes : 0;
}
inline constexpr size_t kRecordFixedBytes = 40;
inline constexpr size_t kMaxRecordBytes = kRecordFixedBytes + 4 * kMaxOutcomeDim + 4;
inline constexpr size_t kAlgorithmNameBytes = 24;
// Slots and headers are buffered whole: the largest write block the journal supports.
inline constexpr size_t kMaxBlockBytes = 256;
static_assert(kHeaderBytes <= kMaxBlockBytes && kMaxRecordBytes <= kMaxBlockBytes);

// What makes two runs the same run: every Explorer setting, the goal space's weights, the
// environment. A resume under a different identity is refused (first_difference()).
struct RunIdentity {
  uint64_t seed = 0;
  uint32_t n_bootstrap = 0;
  uint32_t n_episodes = 0;
  float sigma = 0.0f;
  float competence_cap = 0.0f;
  float window = 0.0f;
  float epsilon = 0.0f;
  float goal_bound = 0.0f;
  uint8_t algorithm = 0;  // curio::Algorithm
  uint8_t outcome_dim = 0;
  uint8_t n_modules = 0;
  uint8_t goal_kind = 0;
  uint8_t competence_measure = 0;
  uint8_t tie_rule = 0;
  uint8_t requery_exploit = 0;
  uint8_t physics = 0xFF;         // 0 kinematic, 1 ODE, 0xFF unknown / real arm
  uint32_t modules_hash = 0;      // FNV-1a of every module's dims
  uint32_t weights_hash = 0;      // learned goal spaces: the encoder weights; 0 for EFR/RPE
  uint32_t environment_hash = 0;  // caller-defined (world parameters); 0 when not used
  char algorithm_name[kAlgorithmNameBytes] = {};  // "MGE-EFR", NUL-padded (UTF-8)
  // The explore strategy's ingredients (ExplorerConfig::frontier_share, sigma_ladder): all 0
  // for SPEC's loop (a version 1 header), else stored in a version 2 header.
  float frontier_share = 0.0f;
  float sigma_ladder[kExploreEpisodesPerStep] = {};
};
// Whether `id` needs a version 2 header (its strategy is not SPEC's).
bool has_strategy(const RunIdentity& id);

enum class IdentityField : uint8_t {
  kNone = 0,
  kAlgorithmName,
  kAlgorithm,
  kSeed,
  kSigma,
  kBootstrap,
  kEpisodes,
  kCompetenceCap,
  kCompetenceMeasure,
  kWindow,
  kEpsilon,
  kGoalBound,
  kGoalKind,
  kOutcomeDim,
  kModules,
  kTieRule,
  kRequeryExploit,
  kPhysics,
  kWeights,
  kEnvironment,
  kStrategy,
};
const char* to_string(IdentityField f);

// The first field in which `a` and `b` differ (kNone: the same run). Floats compare by bits.
IdentityField first_difference(const RunIdentity& a, const RunIdentity& b);

enum class RecordType : uint8_t { kEpisode = 1, kSkip = 2 };

// One journaled episode: what replay feeds to Explorer::observe() and what the host's result
// files need besides (ball, distractor, grasp). kind/module/exploit/progress are what the
// explorer said at the time: replay recomputes them and checks they agree.
struct EpisodeEntry {
  uint32_t episode = 0;  // archive index
  uint8_t kind = 0;      // curio::EpisodeKind
  int8_t module = -1;
  bool exploit = false;
  bool grasped = false;
  uint8_t attempts = 0;
  uint8_t outcome_dim = 0;
  float ball[2] = {};
  float distractor[2] = {};
  float progress = 0.0f;
  float outcome[kMaxOutcomeDim] = {};
};

// A decoded slot.
struct Record {
  RecordType type = RecordType::kEpisode;
  uint32_t slot = 0;
  uint32_t skipped_slot = 0;  // kSkip: the torn slot it acknowledges
  EpisodeEntry entry;         // kEpisode
};

constexpr uint32_t round_up(uint32_t n, uint32_t block) { return (n + block - 1) / block * block; }
constexpr uint32_t record_bytes(int outcome_dim) {
  return static_cast<uint32_t>(kRecordFixedBytes + 4 * static_cast<size_t>(outcome_dim) + 4);
}

// Byte-level codecs (no storage). Encoders write exactly the unpadded size and return it.
void encode_identity(const RunIdentity& id, uint8_t out[kIdentityBytes]);
void decode_identity(const uint8_t in[kIdentityBytes], RunIdentity* id);
size_t encode_header(const RunIdentity& id, uint16_t header_stride, uint16_t record_stride,
                     uint16_t write_block, uint8_t out[kHeaderBytes]);
struct Header {
  RunIdentity identity;
  uint16_t version = 0;
  uint16_t header_stride = 0;
  uint16_t record_stride = 0;
  uint16_t write_block = 0;
  uint32_t crc = 0;  // the run's nonce in record CRCs
};
enum class DecodeResult : uint8_t { kOk, kErased, kBadMagic, kBadCrc, kBadVersion, kBadLayout };
const char* to_string(DecodeResult r);
DecodeResult decode_header(const uint8_t* in, size_t len, Header* h);
size_t encode_record(const Record& r, int outcome_dim, uint32_t nonce,
                     uint8_t out[kMaxRecordBytes]);
// `len` ≥ record_bytes(outcome_dim); kErased when all `len` bytes are 0xFF.
DecodeResult decode_record(const uint8_t* in, size_t len, int outcome_dim, uint32_t nonce,
                           Record* r);

}  // namespace curio::journal
