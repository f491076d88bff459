// A run's journal file on the host (host_tools/journal/run_journal.hpp).
#include "host_tools/journal/run_journal.hpp"

#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "firmware/explore/fnv1a.hpp"
#include "firmware/journal/replay.hpp"
#include "host_tools/experiment/explore_strategies.hpp"
#include "host_tools/experiment/representations.hpp"

namespace curio::journal::host {

namespace {

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

const char* physics_name(uint8_t p) {
  return p == 0 ? "kinematic" : p == 1 ? "ODE" : "unknown (real arm)";
}

// The explore strategy by its curio-lab name when it is one, else by its ingredients.
std::string strategy_text(const RunIdentity& id) {
  for (const lab::ExploreStrategy& st : lab::explore_strategies()) {
    bool same = std::memcmp(&st.frontier_share, &id.frontier_share, sizeof(float)) == 0;
    for (int i = 0; i < kExploreEpisodesPerStep; ++i)
      same = same && std::memcmp(&st.sigma_ladder[i], &id.sigma_ladder[i], sizeof(float)) == 0;
    if (same) return st.name;
  }
  return "frontier share " + number(id.frontier_share) + ", σ ladder ×(" +
         number(id.sigma_ladder[0]) + "," + number(id.sigma_ladder[1]) + "," +
         number(id.sigma_ladder[2]) + "," + number(id.sigma_ladder[3]) + ")";
}

std::string field_value(const RunIdentity& id, IdentityField f) {
  switch (f) {
    case IdentityField::kAlgorithmName:
      return id.algorithm_name;
    case IdentityField::kAlgorithm:
      return std::to_string(id.algorithm);
    case IdentityField::kSeed:
      return std::to_string(id.seed);
    case IdentityField::kSigma:
      return number(id.sigma);
    case IdentityField::kBootstrap:
      return std::to_string(id.n_bootstrap);
    case IdentityField::kEpisodes:
      return std::to_string(id.n_episodes);
    case IdentityField::kCompetenceCap:
      return number(id.competence_cap);
    case IdentityField::kCompetenceMeasure:
      return id.competence_measure == 0 ? "clip" : "scale";
    case IdentityField::kWindow:
      return number(id.window);
    case IdentityField::kEpsilon:
      return number(id.epsilon);
    case IdentityField::kGoalBound:
      return number(id.goal_bound);
    case IdentityField::kGoalKind:
      return id.goal_kind == 0 ? "uniform box" : "clipped normal";
    case IdentityField::kOutcomeDim:
      return std::to_string(id.outcome_dim);
    case IdentityField::kModules: {
      char b[48];
      std::snprintf(b, sizeof b, "%d modules (layout %08x)", id.n_modules,
                    static_cast<unsigned>(id.modules_hash));
      return b;
    }
    case IdentityField::kTieRule:
      return id.tie_rule == static_cast<uint8_t>(TieRule::kLatest) ? "latest" : "earliest";
    case IdentityField::kRequeryExploit:
      return id.requery_exploit ? "on" : "off";
    case IdentityField::kPhysics:
      return physics_name(id.physics);
    case IdentityField::kWeights:
    case IdentityField::kEnvironment: {
      char b[16];
      std::snprintf(b, sizeof b, "%08x",
                    static_cast<unsigned>(f == IdentityField::kWeights ? id.weights_hash
                                                                       : id.environment_hash));
      return b;
    }
    case IdentityField::kStrategy:
      return strategy_text(id);
    case IdentityField::kNone:
      break;
  }
  return "";
}

}  // namespace

RunIdentity identity_of(const lab::RunSpec& spec, const ExplorerConfig& config, uint8_t physics,
                        uint32_t environment_hash) {
  if (config.goal_scale != 1.0f)
    throw std::invalid_argument("the journal's run identity has no goal-scale field: "
                                "journal only runs with goal_scale 1");
  RunIdentity id;
  id.seed = config.seed;
  id.n_bootstrap = static_cast<uint32_t>(config.n_bootstrap);
  id.n_episodes = static_cast<uint32_t>(config.n_episodes);
  id.sigma = config.sigma;
  id.competence_cap = config.competence_cap;
  id.window = config.window;
  id.epsilon = config.epsilon;
  id.goal_bound = config.goal_bound;
  id.algorithm = static_cast<uint8_t>(config.algorithm);
  id.outcome_dim = static_cast<uint8_t>(config.outcome_dim);
  id.n_modules = static_cast<uint8_t>(config.n_modules);
  id.goal_kind = static_cast<uint8_t>(config.goal_kind);
  id.competence_measure = static_cast<uint8_t>(config.competence_measure);
  id.tie_rule = static_cast<uint8_t>(config.tie_rule);
  id.requery_exploit = config.requery_exploit ? 1 : 0;
  id.physics = physics;
  Fnv1a m;
  for (int k = 0; k < config.n_modules && k < kMaxModules; ++k) {
    m.add_u32(static_cast<uint32_t>(config.modules[k].n_dims));
    for (int d = 0; d < config.modules[k].n_dims; ++d) m.add_u32(config.modules[k].dims[d]);
  }
  id.modules_hash = m.h;
  if (spec.algorithm.outcome == lab::OutcomeSource::kLatents) {
    // The weights by their provenance (the trainer's input hash) and name.
    Fnv1a w;
    const lab::Representation* rep = lab::find_representation(spec.algorithm.representation);
    const std::string tag =
        spec.algorithm.representation + ":" + (rep ? rep->inputs_sha256 : std::string("missing"));
    for (char c : tag) w.add_u32(static_cast<uint8_t>(c));
    id.weights_hash = w.h;
  }
  id.environment_hash = environment_hash;
  id.frontier_share = config.frontier_share;
  for (int i = 0; i < kExploreEpisodesPerStep; ++i) id.sigma_ladder[i] = config.sigma_ladder[i];
  std::strncpy(id.algorithm_name, spec.algorithm.name.c_str(), kAlgorithmNameBytes - 1);
  return id;
}

std::string describe_difference(const RunIdentity& journal, const RunIdentity& run) {
  const IdentityField f = first_difference(journal, run);
  if (f == IdentityField::kNone) return "";
  const std::string name = to_string(f);
  return "journal is " + name + " " + field_value(journal, f) + ", this run is " + name + " " +
         field_value(run, f);
}

std::string describe(const RunIdentity& id) {
  const std::string strategy = has_strategy(id) ? " (explore " + strategy_text(id) + ")" : "";
  return std::string(id.algorithm_name) + strategy + " seed " + std::to_string(id.seed) + " σ " +
         number(id.sigma) + ", " + std::to_string(id.n_bootstrap) + " + " +
         std::to_string(id.n_episodes) + " episodes";
}

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
