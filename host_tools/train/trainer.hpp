// `curio-train train`: the training loop with progress lines, CSV log, periodic
// held-out evaluation, checkpoints (resumable) and the final figures and factor report.
#pragma once
#include <cstdint>
#include <string>

#include "host_tools/vae/recipe.hpp"

namespace curio::train {

struct TrainOptions {
  Recipe recipe;
  std::string out_dir;
  bool resume = false;
  int64_t checkpoint_every = 1000;
  int64_t log_every = 100;
  int64_t eval_every = 1000;   // held-out factor check (0: never); written to eval.jsonl
  int64_t eval_images = 2000;
  int64_t report_images = 10000;  // final factor report (0: skip)
  int threads = 1;
};

// What is wrong with a recipe's options ("--lr must be > 0"), "" when nothing is: curio-train
// checks the command line with it (a usage error, exit 2) before anything is written.
std::string recipe_problem(const Recipe& recipe);

// Returns the process exit code: 0 done, 130/143 stopped by SIGINT/SIGTERM after saving a
// checkpoint. Throws std::runtime_error on a bad recipe (recipe_problem, also for the rows
// count of a --scenes file) or I/O failures.
int run_training(const TrainOptions& options);

// Loads the checkpoint file `checkpoint`, renders `images` held-out scenes and writes
// factor_report.json, traversal.png and reconstruction.png into the folder that holds it.
// Returns 0 when the model passes its criteria, 1 when it does not.
int run_report(const std::string& checkpoint, int64_t images, int threads);

// `curio-train unmix`: loads `from` (a checkpoint file), unmixes its active latents with FastICA
// on `images` training images of its recipe's data (latent_unmixing.hpp), prints the held-out
// factor check before and after, and writes <out>/checkpoint.pt for a following
// `train --init-from`. Returns 0.
int run_unmix(const std::string& from, const std::string& out_dir, int64_t images, int threads);

}  // namespace curio::train
