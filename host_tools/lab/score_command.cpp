#include "host_tools/lab/score_command.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "host_tools/experiment/campaign_config.hpp"
#include "host_tools/experiment/report.hpp"
#include "host_tools/experiment/run_explorer.hpp"
#include "host_tools/experiment/run_recorder.hpp"
#include "host_tools/journal/run_journal.hpp"
#include "host_tools/cli/command_line.hpp"

namespace curio::lab {

namespace fs = std::filesystem;
namespace jh = journal::host;

CLI::App* add_score_command(CLI::App& app, ScoreCommandOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "score",
      "Score a saved run afterwards: its exploration ratio, summaries and plots from final ball "
      "positions given in a CSV (episode,ball_x,ball_y[,distractor_x,distractor_y[,grasped]], from any "
      "tracker), the run itself rebuilt from its journal (e.g. curio-controller --camera COMMAND, "
      "which has no ground truth)");
  cmd->add_option("--run", options.run_dir, "The run's output folder (holds journal.bin)")->required();
  cmd->add_option("--positions", options.positions, "CSV of every episode's final positions")
      ->required();
  cmd->add_option("--out", options.out, "Output folder (default: RUN/score)")
      ->check(curio::cli::kOutputFolder);
  cmd->add_flag("--quiet", options.quiet, "Only the result line");
  return cmd;
}

std::string read_positions(const std::string& path, std::map<long, FinalPosition>* out) {
  std::ifstream in(path);
  if (!in) return path + ": cannot be read";
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.empty() || line == "\r") continue;
    std::vector<std::string> fields;
    std::stringstream ss(line);
    for (std::string f; std::getline(ss, f, ',');) fields.push_back(f);
    const auto number = [](const std::string& s, double* v) {
      char* end = nullptr;
      *v = std::strtod(s.c_str(), &end);
      return !s.empty() && end != s.c_str() && (*end == '\0' || *end == '\r' || *end == ' ');
    };
    double e = 0, x = 0, y = 0;
    if (n == 1 && !number(fields.empty() ? "" : fields[0], &e)) continue;  // a header
    if (fields.size() != 3 && fields.size() != 5 && fields.size() != 6)
      return path + ":" + std::to_string(n) + ": expected 3, 5 or 6 fields (episode,ball_x,ball_y"
             "[,distractor_x,distractor_y[,grasped]]), got " + std::to_string(fields.size());
    if (!number(fields[0], &e) || e < 0 || e != static_cast<double>(static_cast<long>(e)))
      return path + ":" + std::to_string(n) + ": episode '" + fields[0] + "' is not a whole number >= 0";
    if (!number(fields[1], &x) || !number(fields[2], &y))
      return path + ":" + std::to_string(n) + ": ball position is not two numbers";
    double g = -1;
    if (fields.size() == 6 && (!number(fields[5], &g) || (g != 0 && g != 1)))
      return path + ":" + std::to_string(n) + ": grasped '" + fields[5] + "' is not 0 or 1";
    (*out)[static_cast<long>(e)] = {x, y, static_cast<int>(g)};
  }
  if (out->empty()) return path + ": no positions";
  return "";
}

int score_command(const ScoreCommandOptions& options) {
  const auto fail = [](const std::string& why) {
    std::fprintf(stderr, "curio-lab score: %s\n", why.c_str());
    return 1;
  };
  const std::string journal_path = (fs::path(options.run_dir) / jh::kJournalFileName).string();
  if (!fs::exists(journal_path))
    return fail(journal_path + ": no journal (the run was not journaled, or --run is not a run's "
                "folder)");
  std::map<long, FinalPosition> positions;
  if (std::string why = read_positions(options.positions, &positions); !why.empty()) return fail(why);
  // Replay a copy: the journal itself is left exactly as it is.
  const std::string out_dir = options.out.empty() ? (fs::path(options.run_dir) / "score").string() : options.out;
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) return fail("cannot create " + out_dir + ": " + ec.message());
  const std::string copy = (fs::path(out_dir) / ".journal.replay").string();
  fs::copy_file(journal_path, copy, fs::copy_options::overwrite_existing, ec);
  if (ec) return fail("cannot copy " + journal_path + ": " + ec.message());
  struct Remove {
    std::string path;
    ~Remove() {
      std::error_code e;
      fs::remove(path, e);
    }
  } remove_copy{copy};
  std::string error;
  auto journal = jh::RunJournal::open(copy, &error);
  if (!journal) return fail(error);
  if (journal->scan().status != journal::JournalStatus::kOk &&
      journal->scan().status != journal::JournalStatus::kFull)
    return fail(journal_path + ": " + jh::describe(journal->scan()));
  const journal::RunIdentity& id = journal->scan().header.identity;
  // The run as its journal names it (the journal's identity is checked against it in full).
  CampaignConfig c;
  c.algorithms = {std::string(id.algorithm_name, strnlen(id.algorithm_name, sizeof id.algorithm_name))};
  c.seeds = {id.seed};
  c.sigmas = {id.sigma};
  c.episodes = static_cast<int>(id.n_episodes);
  c.bootstrap = static_cast<int>(id.n_bootstrap);
  c.competence_clip = id.competence_cap;
  c.window = id.window;
  c.epsilon = id.epsilon;
  c.tie_rule = static_cast<TieRule>(id.tie_rule);
  c.competence_measure = static_cast<CompetenceMeasure>(id.competence_measure);
  c.physics = id.physics == 1 ? sim::Physics::kOde : sim::Physics::kKinematic;
  c.out_dir = out_dir;
  c.quiet = options.quiet;
  if (const auto problems = validate_campaign(c); !problems.empty())
    return fail(journal_path + ": its run cannot be rebuilt: " + problems.front());
  RunResult result;
  result.spec = expand_runs(c).front();
  RunExplorer x;
  if (!make_run_explorer(result.spec, &x, &error)) return fail(error);
  const journal::RunIdentity rebuilt =
      jh::identity_of(result.spec, x.config, id.physics, id.environment_hash);
  if (std::string diff = jh::describe_difference(id, rebuilt); !diff.empty())
    return fail(journal_path + ": the rebuilt run differs from the journaled one: " + diff);
  RunRecorder recorder(*x.explorer, x.rep, &result);
  long missing = -1;
  const auto replayed = [&](const journal::EpisodeEntry& e, const Explorer&) {
    const auto p = positions.find(static_cast<long>(e.episode));
    if (p == positions.end()) {
      if (missing < 0) missing = static_cast<long>(e.episode);
      recorder.record_episode(e.exploit, e.module, e.progress, 2.0f, 2.0f, e.grasped);  // no cell
      return;
    }
    const bool grasped = p->second.grasped < 0 ? e.grasped : p->second.grasped == 1;
    recorder.record_episode(e.exploit, e.module, e.progress, static_cast<float>(p->second.ball_x),
                            static_cast<float>(p->second.ball_y), grasped);
  };
  std::string notice;
  if (!journal->resume(id, x.explorer.get(), replayed, &error, &notice)) return fail(error);
  if (missing >= 0)
    return fail(options.positions + ": no position for episode " + std::to_string(missing) +
                " (every journaled episode needs one)");
  const int episodes = x.explorer->episode();
  if (x.explorer->done()) recorder.finish();
  // A run that stopped early is scored up to its last journaled episode: its checkpoints end
  // there.
  while (result.ratio.size() < result.checkpoints.size()) result.checkpoints.pop_back();
  const std::vector<RunResult> results = {result};
  auto summary = summarize_campaign(c, results, 0.0);
  summary["scored"] = {{"run", options.run_dir},
                       {"positions", options.positions},
                       {"episodes", episodes},
                       {"complete", x.explorer->done()}};
  std::vector<std::string> warnings;
  if (!write_report(c, results, summary, &warnings, &error)) return fail(error);
  for (const auto& w : warnings) std::fprintf(stderr, "curio-lab score: warning: %s\n", w.c_str());
  std::printf("exploration ratio after %d episodes: %.4f; results in %s/\n", episodes,
              result.ratio.empty() ? 0.0 : result.ratio.back(), out_dir.c_str());
  if (!result.verdicts.empty())
    std::printf("controllable (from learning progress alone): {%s}\n", verdict_text(result).c_str());
  return 0;
}

}  // namespace curio::lab
