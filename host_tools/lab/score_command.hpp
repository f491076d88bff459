// `curio-lab score --run DIR --positions CSV [--out OUT]`: the exploration ratio of a run whose
// final positions were not known while it ran (curio-controller --camera COMMAND: a camera on
// the controller's computer, no tracker), measured afterwards from positions a tracker gives.
//
// The run is rebuilt from its journal (DIR/journal.bin): the explorer replays every journaled
// episode, as a --resume does, so the modules, exploits, learning progress and interest are the
// run's own; each episode's final ball position comes from the CSV instead of the journal. The
// report is curio-lab's (ratio at every checkpoint, runs/*.csv, summary.json/.md, the ratio,
// interest and ball-position plots), so a scored run reads like a simulated one; on a run that
// had the ground truth, scoring it with the same positions gives the same figures.
//
// CSV: one line per episode, `episode,ball_x,ball_y[,distractor_x,distractor_y[,grasped]]` (a
// header line whose first field is not a number is skipped); an episode listed twice takes its
// last line (a replayed episode); every journaled episode must be listed. Grasps (0 or 1) count
// in the grasp column of the results; without the column, the journal's (none for a run
// without ground truth).
#pragma once
#include <map>
#include <string>

#include <CLI/CLI.hpp>

namespace curio::lab {

struct ScoreCommandOptions {
  std::string run_dir;
  std::string positions;
  std::string out;  // "" : RUN/score
  bool quiet = false;
};

CLI::App* add_score_command(CLI::App& app, ScoreCommandOptions& options);

// Exit status: 0; 1 the journal or the CSV cannot be read or does not fit the run, a file
// cannot be written.
int score_command(const ScoreCommandOptions& options);

// The CSV's positions by episode: [ball x, ball y]. "" or one line naming the file, line and
// problem (exposed for tests).
struct FinalPosition {
  double ball_x = 0, ball_y = 0;
  int grasped = -1;  // 0, 1, or -1: not given
};
std::string read_positions(const std::string& path, std::map<long, FinalPosition>* out);

}  // namespace curio::lab
