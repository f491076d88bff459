// curio-lab: the experiment runner. Runs exploration campaigns (algorithms × seeds × σ)
// in-process against the simulated arm on all cores, splits them into tasks and merges them
// back, writes Slurm job arrays, and measures throughput. One file per command:
//   run, paper     run_command.hpp     a campaign on this machine, or one task's share
//   merge          merge_command.hpp   task folders back into one report
//   slurm, slurm-train  slurm_command.hpp
//   bench          bench_command.hpp
//   score          score_command.hpp   a saved run's ratio from positions given afterwards
// Exit status: 0 done; 1 a runtime failure or a failed run; 2 a usage error (one line naming
// the option); 130/143 stopped by SIGINT/SIGTERM (rerun the command to resume).
#include <CLI/CLI.hpp>

#include "host_tools/cli/command_line.hpp"
#include "host_tools/lab/bench_command.hpp"
#include "host_tools/lab/merge_command.hpp"
#include "host_tools/lab/run_command.hpp"
#include "host_tools/lab/score_command.hpp"
#include "host_tools/lab/slurm_command.hpp"

int main(int argc, char** argv) {
  using namespace curio::lab;
  CLI::App app{
      "curio-lab: runs curiosity-driven exploration campaigns on the simulated Arm-2-Balls world\n"
      "(in-process, all cores) and writes exploration ratios, summaries and plots.",
      "curio-lab"};
  app.require_subcommand(1);
  CampaignOptions campaign;
  RunCommandOptions run_options;
  BenchCommandOptions bench_options;
  MergeCommandOptions merge_options;
  SlurmCommandOptions slurm_options;
  ScoreCommandOptions score_options;
  CLI::App* run = add_run_command(app, campaign, run_options);
  CLI::App* bench = add_bench_command(app, campaign, bench_options);
  CLI::App* paper = add_paper_command(app, campaign, run_options);
  CLI::App* merge = add_merge_command(app, merge_options);
  CLI::App* slurm = add_slurm_command(app, campaign, slurm_options);
  CLI::App* slurm_train = add_slurm_train_command(app, slurm_options);
  CLI::App* score = add_score_command(app, score_options);
  if (const auto code = curio::cli::parse(app, argc, argv)) return *code;
  if (run->parsed()) return run_command(*run, campaign, run_options);
  if (paper->parsed()) return paper_command(*paper, campaign, run_options);
  if (merge->parsed()) return merge_command(*merge, merge_options);
  if (slurm->parsed()) return slurm_command(*slurm, campaign, slurm_options);
  if (slurm_train->parsed()) return slurm_train_command(*slurm_train, slurm_options);
  if (bench->parsed()) return bench_command(*bench, campaign, bench_options);
  if (score->parsed()) return score_command(score_options);
  return curio::cli::kUsageError;
}
