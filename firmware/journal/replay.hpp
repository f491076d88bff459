// Resume by replay: the Explorer's state (archive, interest, goal history, PRNG streams) is a
// pure function of its config and the outcomes it observed, so feeding the journaled
// outcomes through propose()/observe() rebuilds it bit for bit, without the arm.
//
//   explorer.init(config);                         // the journal's run (identity checked)
//   JournalReader reader; reader.open(&storage, scan);
//   ReplayReport rep;
//   if (replay_journal(reader, explorer, &observer, &rep) != JournalStatus::kOk) ...
//   // explorer.episode() == scan.episodes; the next propose() is the episode in flight
//
// Each record is checked against what the explorer says during replay (episode index, kind,
// module, exploit flag, learning progress bits): a mismatch is kReplayMismatch at
// rep.episode, so a journal from another build or configuration is caught, not absorbed.
// Header-only: it works with every archive capacity the explorer is built with.
#pragma once
#include <cstdint>
#include <cstring>

#include "firmware/explore/explorer.hpp"
#include "firmware/journal/journal.hpp"

namespace curio::journal {

class ReplayObserver {
 public:
  // After explorer.observe() of `entry` (the explorer has advanced past it).
  virtual void on_replayed(const EpisodeEntry& entry, const Explorer& explorer) = 0;

 protected:
  ~ReplayObserver() = default;
};

struct ReplayReport {
  uint32_t episodes = 0;  // replayed
  uint32_t episode = 0;   // kReplayMismatch / errors: the episode concerned
  const char* what = "";  // which check failed
};

inline bool same_bits(float a, float b) {
  uint32_t x, y;
  std::memcpy(&x, &a, 4);
  std::memcpy(&y, &b, 4);
  return x == y;
}

inline JournalStatus replay_journal(JournalReader& reader, Explorer& explorer,
                                    ReplayObserver* observer, ReplayReport* report) {
  ReplayReport local;
  ReplayReport& rep = report != nullptr ? *report : local;
  rep = ReplayReport{};
  if (!explorer.initialised() || explorer.episode() != 0) return JournalStatus::kInvalidArgument;
  float theta[kThetaDim];
  for (;;) {
    EpisodeEntry e;
    bool end = false;
    const JournalStatus s = reader.next(&e, &end);
    if (s != JournalStatus::kOk) return s;
    if (end) return JournalStatus::kOk;
    rep.episode = e.episode;
    auto mismatch = [&](const char* what) {
      rep.what = what;
      return JournalStatus::kReplayMismatch;
    };
    if (explorer.done()) return mismatch("more records than the run has episodes");
    if (static_cast<uint32_t>(explorer.episode()) != e.episode) return mismatch("episode index");
    if (e.outcome_dim != explorer.config().outcome_dim) return mismatch("outcome dimension");
    if (explorer.propose(theta) != Status::kOk) return mismatch("propose");
    if (static_cast<uint8_t>(explorer.kind()) != e.kind) return mismatch("episode kind");
    if (explorer.module() != e.module) return mismatch("module");
    const bool exploit = explorer.kind() == EpisodeKind::kExploit && explorer.module() >= 0;
    if (exploit != e.exploit) return mismatch("exploit flag");
    if (explorer.observe(e.outcome) != Status::kOk) return mismatch("observe");
    if (exploit && !same_bits(explorer.last_progress(), e.progress))
      return mismatch("learning progress");
    ++rep.episodes;
    if (observer != nullptr) observer->on_replayed(e, explorer);
  }
}

}  // namespace curio::journal
