// `curio-lab run --out D` (and `paper`): a campaign run on this machine into D. D is task 0 of
// 1 in campaign_task.hpp's layout (manifest.json; records/run-<i>.cbor, written atomically as
// each run ends) with the report (host_tools/experiment/report.hpp) beside it. What happens to
// a D already used:
//   D absent or empty                        the campaign runs
//   D holds this campaign, finished          nothing runs; the report is written again
//   D holds this campaign, unfinished        resumed: recorded runs are skipped, the others run;
//                                            a run stopped part way continues from its journal
//   D holds another campaign (another         refused, naming the differences; with `replace`
//     configuration, a task of a split        the old campaign's files (report_files of its
//     campaign, or an older curio-lab's       configuration, its records, its manifest) are
//     results without manifest.json)          removed first, and only those, then it runs
//   D holds other files and no campaign      refused, `replace` or not (curio-lab cannot tell
//                                            its files from the user's)
// `replace` on this very campaign removes its files and runs every run again.
// Each run in flight journals its episodes to records/run-<i>.journal (host_tools/journal:
// the firmware's journal format through a file), removed once its record is written; a run
// stopped (Ctrl-C) or killed part way is resumed by replaying that journal into a fresh
// explorer and positioning the world at the next episode, so it ends as an uninterrupted run
// does. The journal is written through the page cache without fdatasync (a simulated run is
// cheap to redo; an fdatasync costs more than a short run here): a kill or Ctrl-C loses
// nothing; after a power cut a torn tail is dropped, and a journal damaged before its tail is
// not replayed: that run starts again from its first episode (a note says so).
#pragma once
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "host_tools/lab/campaign_runner.hpp"

namespace curio::lab {

struct LocalCampaignOptions {
  bool replace = false;
  bool journal = true;  // false: a stopped run starts again from its first episode
  const std::atomic<bool>* stop = nullptr;  // Ctrl-C: runs in flight end, none starts
  std::FILE* log = nullptr;  // each note is printed here ("curio-lab: ...") as it arises
};

struct LocalCampaignOutcome {
  size_t runs = 0;                 // in the campaign
  size_t skipped = 0;              // recorded by an earlier invocation
  size_t ran = 0;                  // finished now (failed ones included)
  size_t failed = 0;               // finished now with an error
  size_t stopped = 0;              // cut short or never started because of a stop request
  size_t removed = 0;              // files of an old campaign removed (replace)
  std::vector<std::string> notes;  // what was done with D, for the user
  double wall_seconds = 0.0;
};

enum class LocalCampaignStatus {
  kOk,       // *results holds every run of the campaign (stopped ones with stopped_early)
  kRefused,  // D is used by something else: nothing was changed (*error says what and why)
  kFailed,   // a file could not be written or removed (*error)
};

LocalCampaignStatus run_local_campaign(const CampaignConfig& config,
                                       const LocalCampaignOptions& options,
                                       std::vector<RunResult>* results,
                                       LocalCampaignOutcome* outcome, std::string* error);

}  // namespace curio::lab
