#include "host_tools/controller/bus_journal.hpp"

#include <filesystem>


namespace curio::app::host {

using journal::JournalStatus;
namespace jh = journal::host;


bool open_bus_journal(const BusRunOptions& options, const ExplorerConfig& config,
                      BusJournal* journal, BusRunResult* out) {
  if (options.journal_path.empty()) return true;
  std::string& error = out->run.error;
  journal->file = jh::RunJournal::open(options.journal_path, &error, options.journal_sync_every);
  if (!journal->file) return false;
  const jh::RunJournal& j = *journal->file;
  const JournalStatus js = j.scan().status;
  // Nothing journaled yet (absent, or cut while being created): a resume starts afresh.
  journal->resume =
      options.resume && js != JournalStatus::kNoJournal && js != JournalStatus::kTornHeader;
  if (options.resume && !journal->resume)
    out->journal_notice =
        "nothing journaled yet (" + jh::describe(j.scan()) + "): starting at episode 0";
  if (!journal->resume) return true;
  if (js != JournalStatus::kOk) {
    error = options.journal_path + ": cannot resume: " + jh::describe(j.scan()) +
            "; nothing was changed";
    return false;
  }
  const journal::RunIdentity& jid = j.scan().header.identity;
  const journal::RunIdentity run = jh::arm_run_identity(options.spec, config, jid.physics);
  const std::string diff = jh::describe_difference(jid, run);
  if (!diff.empty()) {
    // The journal keeps the world as its hash only (firmware/protocol/world_identity.hpp).
    const std::string hint =
        journal::first_difference(jid, run) != journal::IdentityField::kEnvironment
            ? ""
            : " (the journal's run had another grasp radius, distractor noise or renderer: "
              "resume with its --grasp-radius and --distractor-noise, against a curio-sim serve "
              "started with them)";
    error = options.journal_path + ": cannot resume: " + diff + hint + "; nothing was changed";
    return false;
  }
  // The run's fault history lives beside the journal (bus_history.hpp), written before the
  // first episode: a journal with episodes and no history file lost it, and a resume would
  // report no faults and one process. Refused, so that deleting a file cannot erase it.
  const std::string& history = options.bus_history_path;
  std::error_code ec;
  if (!history.empty() && j.scan().episodes > 0 &&
      !std::filesystem::exists(std::filesystem::symlink_status(history, ec))) {
    error = options.journal_path + ": cannot resume: it holds " +
            std::to_string(j.scan().episodes) + " episodes, but " + history +
            " (the run's fault, replay and process counts) is missing; a resume would report "
            "none of them. Restore that file, or start over with --replace; nothing was changed";
    return false;
  }
  return true;
}

bool start_bus_journal(BusJournal& journal, const BusRunOptions& options,
                       const ExplorerConfig& config, Explorer& explorer, lab::RunRecorder& recorder,
                       Controller& controller, BusRunResult* out) {
  if (!journal.file) return true;
  const journal::RunIdentity id = jh::arm_run_identity(options.spec, config, out->physics);
  const auto replayed = [&](const journal::EpisodeEntry& e, const Explorer&) {
    recorder.record_episode(e.exploit, e.module, e.progress, e.ball[0], e.ball[1], e.grasped);
  };
  const bool ok = journal.resume ? journal.file->resume(id, &explorer, replayed, &out->run.error,
                                                        &out->journal_notice)
                                 : journal.file->start(id, &out->run.error);
  if (!ok) return false;
  out->resumed_episodes = explorer.episode();
  controller.set_journal(&journal.file->writer());
  if (options.progress && options.resume)
    std::fprintf(options.progress, "curio-controller: resume %s: %s; continuing at episode %d\n",
                 options.journal_path.c_str(), out->journal_notice.c_str(), explorer.episode());
  return true;
}

OutFolder prepare_out_folder(const std::string& out_dir, const std::string& journal_path,
                             bool resume, bool replace, std::string* message) {
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) {
    *message = "cannot create --out " + out_dir + ": " + ec.message();
    return OutFolder::kCannotCreate;
  }
  if (resume || replace || !std::filesystem::exists(journal_path)) return OutFolder::kReady;
  std::string why;
  const auto j = jh::RunJournal::open(journal_path, &why);
  if (j && !j->has_journal()) return OutFolder::kReady;
  *message = journal_path + " holds a journal (" + (j ? jh::describe(j->scan()) : why) +
             "); continue it with --resume, or start over with --replace";
  return OutFolder::kHoldsJournal;
}

}  // namespace curio::app::host
