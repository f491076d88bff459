// Status codes of the exploration core. Firmware reports errors by value (no exceptions);
// every function that can fail returns one of these and leaves its object unchanged on error.
#pragma once
#include <cstdint>

namespace curio {

enum class Status : uint8_t {
  kOk = 0,
  kFull,              // archive or history has no room left
  kInvalidConfig,     // a config field is out of range (see ExplorerConfig)
  kCapacityTooSmall,  // n_bootstrap + n_episodes > kArchiveCapacity
  kNotInitialised,    // init() has not succeeded yet
  kDone,              // all episodes have been observed
  kNoPendingEpisode,  // observe() without a preceding propose()
  kNonFiniteOutcome,  // outcome holds NaN or ±inf; nothing stored
  kInvalidArgument,   // e.g. a null pointer or an index out of range
};

// Short stable name for logs ("ok", "full", ...).
constexpr const char* to_string(Status s) {
  switch (s) {
    case Status::kOk:
      return "ok";
    case Status::kFull:
      return "full";
    case Status::kInvalidConfig:
      return "invalid_config";
    case Status::kCapacityTooSmall:
      return "capacity_too_small";
    case Status::kNotInitialised:
      return "not_initialised";
    case Status::kDone:
      return "done";
    case Status::kNoPendingEpisode:
      return "no_pending_episode";
    case Status::kNonFiniteOutcome:
      return "non_finite_outcome";
    case Status::kInvalidArgument:
      return "invalid_argument";
  }
  return "unknown";
}

}  // namespace curio
