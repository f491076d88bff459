#include "host_tools/lab/local_campaign.hpp"

#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <set>

#include <nlohmann/json.hpp>

#include "host_tools/common/atomic_file.hpp"
#include "host_tools/experiment/campaign_json.hpp"
#include "host_tools/experiment/report.hpp"
#include "host_tools/journal/run_journal.hpp"
#include "host_tools/lab/campaign_task.hpp"
#include "host_tools/lab/run_record.hpp"
#include "host_tools/lab/scene_log.hpp"

namespace curio::lab {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// What D holds before the campaign starts.
struct OutDir {
  enum Kind { kFresh, kThisCampaign, kOtherCampaign, kForeign } kind = kFresh;
  std::optional<CampaignConfig> old;  // the campaign whose files D holds (not kFresh/kForeign)
  std::vector<size_t> old_records;    // run indices its manifest lists
  std::string what;                   // kOtherCampaign / kForeign: why, for the message
};

std::string rel(const std::string& dir, const std::string& name) {
  return (fs::path(dir) / name).string();
}

OutDir inspect(const CampaignConfig& c) {
  OutDir d;
  const std::string& dir = c.out_dir;
  std::error_code ec;
  if (!fs::exists(dir, ec)) return d;
  if (!fs::is_directory(dir, ec)) {
    d.kind = OutDir::kForeign;
    d.what = dir + " is not a folder";
    return d;
  }
  if (fs::is_empty(dir, ec)) return d;
  const json here = campaign_to_json(c);
  if (fs::exists(manifest_path(dir), ec)) {
    std::string why;
    const auto m = read_task_manifest(dir, &why);
    std::optional<CampaignConfig> old;
    if (m) old = campaign_from_json(m->campaign, &why);
    if (!m || !old) {
      d.kind = OutDir::kForeign;
      d.what = dir + " has a manifest.json this curio-lab cannot read (" + why + ")";
      return d;
    }
    d.old = old;
    d.old_records = m->runs;
    if (m->tasks == 1 && m->campaign == here) {
      d.kind = OutDir::kThisCampaign;
      return d;
    }
    d.kind = OutDir::kOtherCampaign;
    if (m->tasks != 1)
      d.what = dir + " is task " + std::to_string(m->task) + " of " + std::to_string(m->tasks) +
               " of a split campaign (curio-lab run --task)";
    else
      d.what = dir + " holds another campaign";
    const auto diff = campaign_differences(m->campaign, here);
    if (!diff.empty()) {
      d.what += " (" + dir + "'s vs this one's:";
      for (const auto& line : diff) d.what += "\n    " + line;
      d.what += ")";
    }
    return d;
  }
  // An older curio-lab's results: a summary.json with the campaign, no manifest, no records.
  std::ifstream f(rel(dir, "summary.json"));
  const json summary = f ? json::parse(f, nullptr, false) : json();
  std::string why;
  if (summary.is_object() && summary.contains("campaign")) {
    if (auto old = campaign_from_json(summary["campaign"], &why)) {
      d.kind = OutDir::kOtherCampaign;
      d.old = old;
      d.what = dir +
               " holds the results of an earlier curio-lab (summary.json, no manifest.json "
               "or run records, so nothing of it can be reused)";
      return d;
    }
  }
  d.kind = OutDir::kForeign;
  d.what = dir +
           " is not empty and holds no curio-lab campaign (no manifest.json), so "
           "curio-lab cannot tell its own files from others";
  return d;
}

// Removes the old campaign's files (its report's, its records, then its manifest) and the
// temporary files a killed writer left of them; nothing else. Folders are removed only empty.
bool remove_old(const std::string& dir, const OutDir& d, size_t* removed, std::string* error) {
  std::set<std::string> names;
  if (d.old)
    for (const auto& f : report_files(*d.old)) names.insert(f);
  for (size_t i : d.old_records)
    for (const char* ext : {".cbor", ".journal"})
      names.insert("records/run-" + std::to_string(i) + ext);
  auto remove = [&](const fs::path& p) {
    std::error_code ec;
    if (fs::remove(p, ec)) ++*removed;
    if (ec) {
      *error = "cannot remove " + p.string() + ": " + ec.message();
      return false;
    }
    return true;
  };
  for (const auto& n : names)
    if (!remove(fs::path(dir) / n)) return false;
  for (const char* sub : {".", "runs", "plots_data", "records"}) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(fs::path(dir) / sub, ec)) {
      const std::string file = e.path().filename().string();
      if (!host::is_temp_name(file)) continue;
      const std::string base =
          (fs::path(sub) / file.substr(0, file.rfind(".tmp."))).lexically_normal().string();
      if ((names.count(base) || base == "manifest.json") && !remove(e.path())) return false;
    }
  }
  if (fs::exists(manifest_path(dir)) && !remove(manifest_path(dir))) return false;
  for (const char* sub : {"runs", "plots_data", "records"}) {
    std::error_code ec;
    if (fs::is_directory(fs::path(dir) / sub, ec) && fs::is_empty(fs::path(dir) / sub, ec))
      fs::remove(fs::path(dir) / sub, ec);
  }
  return true;
}

std::string journal_path(const std::string& dir, size_t index) {
  return (fs::path(dir) / "records" / ("run-" + std::to_string(index) + ".journal")).string();
}

// The hooks that journal run `index` as it runs and, on a later start, replay its journal:
// the run continues at the episode in flight when it was stopped.
RunHooks journal_hooks(const RunSpec& spec, const std::string& path, size_t index,
                       const std::function<void(std::string)>& note) {
  struct State {
    std::unique_ptr<journal::host::RunJournal> journal;
  };
  auto state = std::make_shared<State>();
  RunHooks h;
  h.resume = [state, spec, path, index, note](
                 const ExplorerConfig& config, Explorer& explorer,
                 const std::function<void(const journal::EpisodeEntry&)>& replayed,
                 std::string* error) {
    state->journal = journal::host::RunJournal::open(path, error, 0);
    if (!state->journal) return false;
    auto& j = *state->journal;
    // A simulated run is cheap to redo: page-cache writes (a kill loses nothing), no fdatasync.
    j.storage().set_fdatasync(false);
    const auto id = journal::host::identity_of(spec, config, spec.physics == sim::Physics::kOde);
    const auto status = j.scan().status;
    if (status == journal::JournalStatus::kNoJournal ||
        status == journal::JournalStatus::kTornHeader)
      return j.start(id, error);
    if (status != journal::JournalStatus::kOk) {
      // Damaged (a power cut): nothing of it is replayed; the run is redone from episode 0,
      // so its results are exactly an uninterrupted run's.
      note("run " + std::to_string(index) + " (" + run_stem(spec) + "): " + path +
           " cannot be "
           "resumed (" +
           journal::host::describe(j.scan()) +
           "): the run starts again from its "
           "first episode");
      return j.start(id, error);
    }
    std::string notice;
    if (!j.resume(
            id, &explorer, [&](const journal::EpisodeEntry& e, const Explorer&) { replayed(e); },
            error, &notice)) {
      *error += " (remove it to run this run from its first episode)";
      return false;
    }
    note("run " + std::to_string(index) + " (" + run_stem(spec) + ") resumed from " + path + ": " +
         notice + "; continuing at episode " + std::to_string(explorer.episode()));
    return true;
  };
  h.on_episode = [state](const journal::EpisodeEntry& e, std::string* error) {
    return state->journal->append(e, error);
  };
  return h;
}

}  // namespace

LocalCampaignStatus run_local_campaign(const CampaignConfig& c, const LocalCampaignOptions& options,
                                       std::vector<RunResult>* results,
                                       LocalCampaignOutcome* outcome, std::string* error) {
  const std::string& dir = c.out_dir;
  std::mutex m;  // notes and write errors come from the worker threads
  const auto note = [&](std::string n) {
    std::lock_guard lock(m);
    if (options.log) {
      std::fprintf(options.log, "curio-lab: %s\n", n.c_str());
      std::fflush(options.log);
    }
    outcome->notes.push_back(std::move(n));
  };
  const OutDir d = inspect(c);
  if (d.kind == OutDir::kForeign) {
    *error = d.what + ": nothing was changed; use an empty or new --out";
    return LocalCampaignStatus::kRefused;
  }
  if (d.kind == OutDir::kOtherCampaign && !options.replace) {
    *error = d.what + "\n  nothing was changed; use another --out, or --replace to remove that " +
             "campaign's files (its records, run CSVs, summaries and plots; nothing else) and " +
             "run this one";
    return LocalCampaignStatus::kRefused;
  }
  if (options.replace && d.kind != OutDir::kFresh) {
    if (!remove_old(dir, d, &outcome->removed, error)) return LocalCampaignStatus::kFailed;
    note("--replace: removed " + std::to_string(outcome->removed) + " files of the campaign " +
         dir + " held");
  }

  std::error_code ec;
  fs::create_directories(fs::path(dir) / "records", ec);
  if (ec) {
    *error = "cannot create " + (fs::path(dir) / "records").string() + ": " + ec.message();
    return LocalCampaignStatus::kFailed;
  }
  if (!host::write_file_atomically(manifest_path(dir), manifest_json(c, 0, 1).dump(2) + "\n",
                                   error))
    return LocalCampaignStatus::kFailed;

  const auto specs = expand_runs(c);
  std::vector<std::string> unusable;
  std::vector<size_t> todo = runs_to_do(c, dir, 0, 1, &unusable);
  for (const auto& u : unusable) note(u);
  std::set<size_t> to_run(todo.begin(), todo.end());
  results->assign(specs.size(), RunResult{});
  for (size_t i = 0; i < specs.size(); ++i) {
    if (to_run.count(i)) continue;
    std::string why;
    auto r = read_run_record(record_path(dir, i), i, specs[i], &why);
    // A recorded run whose scene log is wanted but missing runs again.
    if (!r || (c.save_scenes && !fs::exists(scene_log_path(dir, specs[i])))) {
      to_run.insert(i);
      continue;
    }
    (*results)[i] = std::move(*r);
    std::error_code ignored;  // a journal left by a kill between the record and its removal
    fs::remove(journal_path(dir, i), ignored);
  }
  todo.assign(to_run.begin(), to_run.end());
  outcome->runs = specs.size();
  outcome->skipped = specs.size() - todo.size();
  if (outcome->skipped > 0)
    note(todo.empty()
             ? "all " + std::to_string(specs.size()) + " runs are recorded in " + dir +
                   "/records: nothing to run, the report is written again (--replace runs them "
                   "again)"
             : "resuming " + dir + ": " + std::to_string(outcome->skipped) + " of " +
                   std::to_string(specs.size()) + " runs recorded (skipped), " +
                   std::to_string(todo.size()) + " to run");
  if (todo.empty()) return LocalCampaignStatus::kOk;

  std::vector<RunSpec> some;
  for (size_t i : todo) some.push_back(specs[i]);
  std::string write_error;
  std::atomic<size_t> failed{0}, ran{0}, stopped{0};
  auto some_results = run_some(
      c, some, &outcome->wall_seconds,
      [&](size_t k, RunResult& r) {
        if (stopped_early(r)) {
          ++stopped;
          return;
        }
        ++ran;
        if (!r.error.empty()) ++failed;
        std::string e;
        // The scene log first: a recorded run has every file the campaign asked of it.
        const bool ok = (!c.save_scenes || write_scene_log(dir, r, &e)) &&
                        write_run_record(record_path(dir, todo[k]), todo[k], r, &e);
        if (!ok) {
          std::lock_guard lock(m);
          write_error = e;
        }
        r.final_distractor = {};  // only the scene log needs it
        std::error_code ignored;  // recorded: its journal has served
        if (ok) fs::remove(journal_path(dir, todo[k]), ignored);
      },
      options.stop,
      [&](size_t k) {
        if (!options.journal) return RunHooks{};
        return journal_hooks(specs[todo[k]], journal_path(dir, todo[k]), todo[k], note);
      });
  for (size_t k = 0; k < todo.size(); ++k) (*results)[todo[k]] = std::move(some_results[k]);
  outcome->ran = ran;
  outcome->failed = failed;
  outcome->stopped = stopped;
  if (!write_error.empty()) {
    *error = write_error;
    return LocalCampaignStatus::kFailed;
  }
  return LocalCampaignStatus::kOk;
}

}  // namespace curio::lab
