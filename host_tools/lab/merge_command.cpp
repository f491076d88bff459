#include "host_tools/lab/merge_command.hpp"

#include <cstdio>

#include "host_tools/cli/command_line.hpp"
#include "host_tools/common/output_folder.hpp"
#include "host_tools/experiment/report.hpp"
#include "host_tools/lab/campaign_merge.hpp"
#include "host_tools/lab/print_report.hpp"

namespace curio::lab {

CLI::App* add_merge_command(CLI::App& app, MergeCommandOptions& o) {
  auto* merge = app.add_subcommand(
      "merge",
      "Merge task folders (run --task I --tasks N) into the campaign's summary, CSVs "
      "and plots, as a local run writes them; lists missing and failed runs");
  merge->add_option("dirs", o.dirs, "Task folders, or folders of task folders")->required();
  merge->add_option("--out", o.out, "Output folder")->required()->check(curio::cli::kOutputFolder);
  merge->add_flag("--allow-partial", o.allow_partial,
                  "Write the report of the runs present even if some are missing or failed");
  merge->add_flag("--json", o.json, "Print the JSON summary to stdout instead of the table");
  return merge;
}

int merge_command(const CLI::App& command, const MergeCommandOptions& o) {
  std::string error;
  auto merged = merge_tasks(o.dirs, &error);
  if (!merged) return cli::usage_error(command, error);
  const size_t expected = expand_runs(merged->config).size();
  for (const auto& m : merged->missing)
    std::fprintf(stderr, "curio-lab merge: missing %s\n", m.c_str());
  for (const auto& f : merged->failed)
    std::fprintf(stderr, "curio-lab merge: failed %s\n", f.c_str());
  const bool partial = !merged->missing.empty() || !merged->failed.empty();
  if (partial && !o.allow_partial) {
    std::fprintf(stderr,
                 "curio-lab merge: %zu of %zu runs missing, %zu failed: nothing written "
                 "(resubmit, or --allow-partial)\n",
                 merged->missing.size(), expected, merged->failed.size());
    return cli::kRuntimeFailure;
  }
  CampaignConfig c = merged->config;
  c.out_dir = o.out;
  const auto claim = host::claim_output_folder_or_say("curio-lab merge", c.out_dir,
                                                      host::OutputAccess::kExclusive);
  if (!claim) return cli::kRuntimeFailure;
  auto summary = summarize_campaign(c, merged->results, merged->run_seconds);
  if (!merged->missing.empty()) summary["missing_runs"] = merged->missing;
  if (!o.json)
    std::printf(
        "curio-lab merge: %zu of %zu runs from %d task folders (wall time below: the "
        "runs' own, summed)\n",
        merged->results.size(), expected, merged->tasks);
  bool written = false;
  const int rc = write_and_print_report(c, merged->results, summary, merged->run_seconds,
                                        {.json = o.json}, &written);
  return written && partial ? 0 : rc;  // failed runs were accepted with --allow-partial
}

}  // namespace curio::lab
