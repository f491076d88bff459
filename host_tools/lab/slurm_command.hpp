// `curio-lab slurm` (a campaign as a Slurm job array of run --task chunks, then a merge job)
// and `curio-lab slurm-train` (one curio-train seed per array task): the scripts are written
// (slurm_jobs.hpp) and, with --submit, submitted; a resubmission runs only what is missing.
#pragma once
#include <string>

#include <CLI/CLI.hpp>

#include "host_tools/lab/campaign_options.hpp"
#include "host_tools/lab/slurm_jobs.hpp"

namespace curio::lab {

struct SlurmCommandOptions {
  std::string out;
  int chunk = 10;
  bool submit = false;
  std::string binary;  // slurm --bin
  SlurmResources resources;
  // slurm-train
  std::string train_script;
  std::string train_seeds;
  std::string trainer;
  std::string done_file = "4_tuned/done";
};

CLI::App* add_slurm_command(CLI::App& app, CampaignOptions& campaign, SlurmCommandOptions& options);
CLI::App* add_slurm_train_command(CLI::App& app, SlurmCommandOptions& options);

// Exit status: 0; 1 sbatch failed; 2 a usage error or a folder that refuses the job.
int slurm_command(const CLI::App& command, const CampaignOptions& campaign,
                  const SlurmCommandOptions& options);
int slurm_train_command(const CLI::App& command, SlurmCommandOptions options);

}  // namespace curio::lab
