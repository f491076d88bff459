// curio-train: trains the SPEC §3 β-VAE / VAE on rendered scenes, reports how its latents
// relate to the scene factors, and exports it for the quantizer. Exit codes as every Curio
// program (host_tools/cli/command_line.hpp): 2 for a usage error (every number has its range),
// 1 for a failure (and a report whose model misses its criteria), 130/143 when SIGINT/SIGTERM
// stops a training (after its checkpoint).
#include <cstdio>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <torch/torch.h>

#include "host_tools/cli/command_line.hpp"
#include "host_tools/train/allocator_tuning.hpp"
#include "host_tools/vae/checkpoint.hpp"
#include "host_tools/train/export_model.hpp"
#include "host_tools/train/trainer.hpp"

namespace {

using namespace curio::train;
using curio::cli::kNonNegative;
using curio::cli::kPositive;

// Every number has its range: a bad one is a usage error (exit 2) before anything is written.
constexpr int64_t kMaxIterations = 1'000'000'000;
constexpr int64_t kMaxImages = 10'000'000;
const CLI::Validator kIterations = CLI::Range(int64_t{1}, kMaxIterations);
const CLI::Validator kIterationOrNever = CLI::Range(int64_t{-1}, kMaxIterations);  // -1: never
const CLI::Validator kImages = CLI::Range(int64_t{1}, kMaxImages);
const CLI::Validator kFactorImages = CLI::Range(int64_t{2}, kMaxImages);  // a correlation needs 2
const CLI::Validator kThreads = CLI::Range(1, 1024);

// A checkpoint to read (--checkpoint, --init-from): a training's folder (its checkpoint.pt, as
// train --out and unmix --out write it) or a checkpoint file.
const char* const kCheckpointHelp = "a training's folder (its checkpoint.pt) or a checkpoint file";
std::string checkpoint_file(const std::string& path) {
  return std::filesystem::is_directory(path) ? checkpoint_path(path) : path;
}

// The shipped recipe's options (train_beta_vae.sh) and where the run goes.
void add_recipe_options(CLI::App* train, TrainOptions& t, std::string& latent_stages) {
  Recipe& r = t.recipe;
  train->add_option("--kind", r.model, "beta-vae (β=150, capacity ramp) or vae (β=1, C=0)")
      ->required()
      ->check(CLI::IsMember({"beta-vae", "vae"}));
  train->add_option("--out", t.out_dir, "output directory (checkpoint, CSV, PNGs, report)")
      ->required()
      ->check(curio::cli::kOutputFolder);
  train->add_option("--iterations", r.iterations, "total training iterations")
      ->check(kIterations)
      ->capture_default_str();
  train->add_option("--batch", r.batch, "batch size")
      ->check(CLI::Range(1, 1'000'000))
      ->capture_default_str();
  train->add_option("--lr", r.lr, "Adam learning rate")->check(kPositive)->capture_default_str();
  train->add_option("--beta", r.beta, "β of the β-VAE")->check(kNonNegative)->capture_default_str();
  train->add_option("--capacity-min", r.capacity_min, "capacity C at the start of the ramp (nats)")
      ->check(kNonNegative)
      ->capture_default_str();
  train->add_option("--capacity-max", r.capacity_max, "capacity C at the end of the ramp (nats)")
      ->check(kNonNegative)
      ->capture_default_str();
  train->add_option("--capacity-iters", r.capacity_iters,
                    "length of the linear C ramp, counted from the end of the warm-up")
      ->check(kNonNegative)
      ->capture_default_str();
  train->add_option("--out-init-scale", r.out_init_scale,
                    "scale of the encoder's output-layer weights after initialisation")
      ->check(kNonNegative)
      ->capture_default_str();
  train->add_option("--init-from", r.init_from,
                    std::string("start from the weights of this checkpoint (fresh optimizer) "
                                "instead of the --init initialisation: ") +
                        kCheckpointHelp)
      ->check(CLI::ExistingPath);
  train->add_option("--latent-stages", latent_stages,
                    "progressive latents, ITER:COUNT,... e.g. 0:2,1000:4,4000:10: from ITER the "
                    "first COUNT latents train, the rest stay at the prior (zero weights) until "
                    "their stage gives them fresh weights (default: all 10 from the start)");
  // The training data.
  train->add_option("--ball-spread", r.ball_spread,
                    "training images draw the ball in [-s,s]^2 (1 = SPEC §3; below 1 is a "
                    "curriculum phase outside the SPEC; held-out checks use the full range)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  train->add_option("--ball-spread-to", r.ball_spread_to,
                    "with --ball-spread-iters: the spread at the end of the ramp")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  train->add_option("--ball-spread-iters", r.ball_spread_iters,
                    "the ball spread moves linearly from --ball-spread to --ball-spread-to over "
                    "this run's first N iterations, the set re-rendered every 1/32 (0: no ramp)")
      ->check(kNonNegative)
      ->capture_default_str();
  train->add_option("--dataset-size", r.dataset_size, "images rendered once and sampled from")
      ->check(kImages)
      ->capture_default_str();
  train->add_option("--scenes", r.scenes_file,
                    "train on the scenes of this CSV (curio-lab run --save-scenes: an "
                    "exploration's own images; sets --dataset-size to its rows) instead of "
                    "SPEC §3's uniform set; held-out checks stay uniform")
      ->check(CLI::ExistingFile);
  train->add_option("--seed", r.seed, "seed of data, init, batches and noise")
      ->check(curio::cli::kSeed)
      ->capture_default_str();
}

// How the run is carried out and logged (none of it changes what it learns).
void add_run_options(CLI::App* train, TrainOptions& t) {
  train->add_option("--threads", t.threads, "LibTorch threads (1 per training on 2 cores)")
      ->check(kThreads)
      ->capture_default_str();
  train->add_flag("--resume", t.resume, "continue from <out>/checkpoint.pt if it exists");
  train->add_option("--checkpoint-every", t.checkpoint_every, "iterations between checkpoints")
      ->check(kIterations)
      ->capture_default_str();
  train->add_option("--log-every", t.log_every, "iterations between progress lines / CSV rows")
      ->check(kIterations)
      ->capture_default_str();
  train->add_option("--eval-every", t.eval_every,
                    "iterations between held-out factor checks (0: never)")
      ->check(kNonNegative)
      ->capture_default_str();
  train->add_option("--eval-images", t.eval_images, "held-out images for those checks")
      ->check(kFactorImages)
      ->capture_default_str();
  train->add_option("--report-images", t.report_images,
                    "held-out images for the final factor report (0: skip; else at least 2)")
      ->check(CLI::Range(int64_t{0}, kMaxImages))
      ->capture_default_str();
}

// Options only the recorded trials use (docs/training.md), listed under their own heading so
// the recipe's options stay readable in --help.
void add_trial_options(CLI::App* train, TrialOptions& trial, bool& default_allocator,
                       bool& keep_denormals) {
  train->option_defaults()->group("Options of the recorded trials (docs/training.md)");
  train->add_option("--lr-warmup", trial.lr_warmup, "iterations of linear lr warm-up from 0")
      ->check(kNonNegative)
      ->capture_default_str();
  train->add_option("--lr-decay-from", trial.lr_decay_from,
                    "iteration from which lr falls linearly to --lr-final at the end (-1: never)")
      ->check(kIterationOrNever)
      ->capture_default_str();
  train->add_option("--lr-final", trial.lr_final, "lr at the last iteration when decaying")
      ->check(kNonNegative)
      ->capture_default_str();
  train->add_option("--warmup", trial.warmup,
                    "plain-VAE iterations (β=1, C=0) before the β-VAE objective")
      ->check(kNonNegative)
      ->capture_default_str();
  train->add_option("--beta-ramp", trial.beta_ramp,
                    "after the warm-up, β rises linearly from 1 to --beta over these iterations")
      ->check(kNonNegative)
      ->capture_default_str();
  train->add_option("--init", trial.init,
                    "weight initialisation: kaiming (Kaiming-normal, zero biases) or torch-default "
                    "(LibTorch's own layer init, as in the reference's PyTorch code)")
      ->check(CLI::IsMember({"kaiming", "torch-default"}))
      ->capture_default_str();
  train->add_option("--vae-window-from", trial.vae_window_from,
                    "first iteration of a plain-VAE window (β=1, C=0) inside the β-VAE run")
      ->check(kIterationOrNever)
      ->capture_default_str();
  train->add_option("--vae-window-to", trial.vae_window_to, "end (exclusive) of that window")
      ->check(kIterationOrNever)
      ->capture_default_str();
  train->add_option("--freeze-encoder-from", trial.freeze_encoder_from,
                    "first iteration at which the encoder's feature layers (convs, fc1, fc2) "
                    "stop training (only enc.fc_out and the decoder learn)")
      ->check(kIterationOrNever)
      ->capture_default_str();
  train->add_option("--freeze-encoder-to", trial.freeze_encoder_to,
                    "end (exclusive) of the encoder freeze (-1: to the end of the run)")
      ->check(kIterationOrNever)
      ->capture_default_str();
  train->add_flag("--freeze-convs-only", trial.freeze_convs_only,
                  "the encoder freeze holds only the 4 convs (fc1 and fc2 keep training)");
  train->add_flag("--freeze-decoder-too", trial.freeze_decoder_too,
                  "the encoder freeze also holds the decoder's fc2 and transposed convs (only "
                  "enc.fc_out and dec.fc1 learn)");
  train->add_option("--prune-by", trial.prune_by,
                    "when a --latent-stages count falls, hold the latents with the lowest recent "
                    "KL (kl) or the smallest reconstruction loss when set to the prior mean (recon)")
      ->check(CLI::IsMember({"kl", "recon"}))
      ->capture_default_str();
  train->add_option("--recycle-every", trial.recycle_every,
                    "every N iterations give the encoder's dormant feature units (convs, fc1, fc2) "
                    "fresh incoming and zero outgoing weights (0: never)")
      ->check(kNonNegative)
      ->capture_default_str();
  train->add_option("--recycle-threshold", trial.recycle_threshold,
                    "a unit is dormant when its mean activation is at most this fraction of its "
                    "layer's mean")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  train->add_flag("--recycle-decoder-too", trial.recycle_decoder_too,
                  "--recycle-every also recycles the decoder's dormant units (fc1, fc2 channels, "
                  "deconv0..2 channels)");
  train->add_option("--revive-at", trial.revive_at,
                    "at this iteration revive a code stuck on one object: recycle the encoder's "
                    "and decoder's dormant units (outgoing weights: --recycle-outgoing-scale), "
                    "fresh read-out for every latent below 0.1 nats (-1: never)")
      ->check(kIterationOrNever)
      ->capture_default_str();
  train->add_flag("--revive-fresh-decoder", trial.revive_fresh_decoder,
                  "the revival re-initialises the whole decoder instead of recycling its units");
  train->add_option("--recycle-outgoing-scale", trial.recycle_outgoing_scale,
                    "outgoing weights of recycled units (--recycle-every, --revive-at): Kaiming x "
                    "this; 0 zeroes them (output unchanged, but no path through two recycled layers)")
      ->check(kNonNegative)
      ->capture_default_str();
  train->add_flag("--freeze-active-readout", trial.freeze_active_readout,
                  "with --init-from: the read-out rows (mu, log var) of the initial model's active "
                  "latents (KL > 0.5) stay fixed, so a KL deficit must lift other latents");
  train->add_flag("--reinit-decoder", trial.reinit_decoder,
                  "with --reinit-after-warmup: re-initialise the whole decoder as well");
  train->add_flag("--reinit-after-warmup", trial.reinit_after_warmup,
                  "re-initialise enc.fc_out and dec.fc1 (and their Adam state) when the "
                  "warm-up ends");
  train->add_flag("--glibc-default-allocator", default_allocator,
                  "benchmark baseline: keep glibc's malloc thresholds (every large tensor is a "
                  "fresh mmap; ~2.4x slower here). Default: freed memory stays in the process");
  train->add_flag("--keep-denormals", keep_denormals,
                  "benchmark baseline: leave denormal floats on (late in training the BCE's exp() "
                  "and sigmoid() produce them; ~1.3x slower steps here). Default: flushed to zero");
  train->option_defaults()->group("Options");
}

// `report`, `export` and `unmix`: their options.
struct ReportOptions {
  std::string checkpoint;
  int64_t images = 10000;
  int threads = 1;
};
struct ExportOptions {
  std::string checkpoint, out, name, made_by;
  int64_t kl_images = 1000;
};
struct UnmixOptions {
  std::string checkpoint, out;
  int64_t images = 10000;
  int threads = 1;
};

CLI::App* add_report_command(CLI::App& app, ReportOptions& o) {
  auto* report = app.add_subcommand(
      "report", "factor report JSON + figures of a trained model, written beside its checkpoint "
                "(exit 0: it meets its criteria, 1: it does not)");
  report->add_option("--checkpoint", o.checkpoint, kCheckpointHelp)
      ->required()
      ->check(CLI::ExistingPath);
  report->add_option("--images", o.images, "held-out images (≥ 2,000 for the verdict)")
      ->check(kFactorImages)
      ->capture_default_str();
  report->add_option("--threads", o.threads, "LibTorch and rendering threads")
      ->check(kThreads)
      ->capture_default_str();
  return report;
}

CLI::App* add_export_command(CLI::App& app, ExportOptions& o) {
  auto* exp = app.add_subcommand("export", "write <name>.cfm (CURIOFM1) and <name>.meta.json");
  exp->add_option("--checkpoint", o.checkpoint, kCheckpointHelp)
      ->required()
      ->check(CLI::ExistingPath);
  exp->add_option("--out", o.out, "destination directory")
      ->required()
      ->check(curio::cli::kOutputFolder);
  exp->add_option("--name", o.name, "file stem, e.g. beta_vae")->required();
  exp->add_option("--kl-images", o.kl_images, "scenes for the per-latent KL (SPEC §2.4)")
      ->check(kImages)
      ->capture_default_str();
  exp->add_option("--made-by", o.made_by,
                  "the command that trained a multi-stage model (stored in the meta JSON beside "
                  "the last stage's recipe), e.g. \"bash host_tools/train/train_beta_vae.sh runs/bvae 2\"");
  return exp;
}

CLI::App* add_unmix_command(CLI::App& app, UnmixOptions& o) {
  auto* unmix = app.add_subcommand(
      "unmix", "re-align a trained model's active latents with FastICA on its training images "
               "(no labels); writes a checkpoint for train --init-from");
  unmix
      ->add_option("--checkpoint", o.checkpoint,
                   std::string("the model to unmix: ") + kCheckpointHelp)
      ->required()
      ->check(CLI::ExistingPath);
  unmix->add_option("--out", o.out, "directory for the unmixed checkpoint.pt")
      ->required()
      ->check(curio::cli::kOutputFolder);
  unmix->add_option("--images", o.images, "training images the ICA sees (at least 100)")
      ->check(CLI::Range(int64_t{100}, kMaxImages))
      ->capture_default_str();
  unmix->add_option("--threads", o.threads, "LibTorch and rendering threads")
      ->check(kThreads)
      ->capture_default_str();
  return unmix;
}

// The train options that only make sense together, checked before anything is written or
// printed: "" when they do, else the usage error's message.
std::string train_problem(TrainOptions& t, const std::string& latent_stages) {
  Recipe& r = t.recipe;
  if (!r.init_from.empty()) r.init_from = checkpoint_file(r.init_from);
  if (r.model == "vae") {
    r.beta = 1.0;
    r.capacity_min = r.capacity_max = 0.0;
  }
  try {
    r.latent_stages = parse_latent_stages(latent_stages);
  } catch (const std::invalid_argument& e) {
    return std::string("--latent-stages: ") + e.what();
  }
  if (t.report_images == 1) return "--report-images must be 0 (skip) or at least 2";
  return recipe_problem(r);
}

int export_checkpoint(const ExportOptions& o) {
  torch::set_num_threads(1);
  Vae model;
  const CheckpointInfo info = load_checkpoint(checkpoint_file(o.checkpoint), model, nullptr);
  model->eval();
  const ExportResult e = export_model(model, info.recipe, info.iteration, o.out, o.name,
                                     o.kl_images, o.made_by);
  fmt::print("wrote {} and {} ({} at iteration {})\n", e.model_path, e.meta_path,
             info.recipe.model, info.iteration);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"curio-train: LibTorch β-VAE / VAE trainer for Curio's goal space (SPEC §3)",
               "curio-train"};
  app.require_subcommand(1);

  TrainOptions t;
  auto* train = app.add_subcommand("train", "train a model (resumable with --resume)");
  std::string latent_stages;
  bool default_allocator = false;
  bool keep_denormals = false;
  add_recipe_options(train, t, latent_stages);
  add_run_options(train, t);
  add_trial_options(train, t.recipe.trial, default_allocator, keep_denormals);
  ReportOptions report_options;
  auto* report = add_report_command(app, report_options);
  ExportOptions export_options;
  auto* exp = add_export_command(app, export_options);
  UnmixOptions unmix_options;
  auto* unmix = add_unmix_command(app, unmix_options);

  if (const auto code = curio::cli::parse(app, argc, argv)) return *code;
  if (*train) {
    if (const std::string problem = train_problem(t, latent_stages); !problem.empty())
      return curio::cli::usage_error(*train, problem);
  }
  // Before LibTorch allocates anything: applies to every subcommand's tensors.
  const std::string allocator = default_allocator
                                    ? "allocator: glibc defaults (--glibc-default-allocator)"
                                    : keep_freed_memory_in_process();
  if (*train && !allocator.empty()) fmt::print("{}\n", allocator);
  // Flush denormal floats to zero on this thread, which runs the training at --threads 1 (as
  // curio-online does): once the decoder is confident, background logits reach ≈ −90 and the
  // BCE's exp() and sigmoid() produce denormals that the CPU handles many times slower.
  // Measured (docs/training.md, Speed): 1.3× late in a run, the same weights bit for bit.
  if (!keep_denormals) at::globalContext().setFlushDenormal(true);
  if (*train)
    fmt::print("{}\n", keep_denormals ? "denormals: kept (--keep-denormals)"
                                       : "denormals: flushed to zero");
  try {
    if (*train) return run_training(t);
    if (*report)
      return run_report(checkpoint_file(report_options.checkpoint), report_options.images,
                        report_options.threads);
    if (*unmix)
      return run_unmix(checkpoint_file(unmix_options.checkpoint), unmix_options.out,
                       unmix_options.images, unmix_options.threads);
    if (*exp) return export_checkpoint(export_options);
  } catch (const std::exception& e) {
    fmt::print(stderr, "curio-train: {}\n", e.what());
    return curio::cli::kRuntimeFailure;
  }
  return 0;
}
