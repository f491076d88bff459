// curio-online: exploration with a goal space learned online from the agent's own images
// (online_run.hpp says what a run does, online_options.hpp its options, online_state.hpp what
// it writes). Exit codes as every Curio program (host_tools/cli/command_line.hpp): 0 done, 1
// runtime failure, 2 usage error (nothing written), 130/143 interrupted by SIGINT/SIGTERM (the default
// action: the checkpoints on disk stay consistent, and --resume continues from the last one).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <torch/torch.h>

#include "host_tools/cli/command_line.hpp"
#include "host_tools/common/atomic_file.hpp"
#include "host_tools/common/output_folder.hpp"
#include "host_tools/online/online_options.hpp"
#include "host_tools/online/online_report.hpp"
#include "host_tools/online/online_run.hpp"
#include "host_tools/online/online_state.hpp"

namespace fs = std::filesystem;
using curio::online::OnlineOptions;

namespace {

constexpr const char* kDescription =
    "curio-online: 400 random episodes, then a beta-VAE (SPEC §3's network, the shipped recipe's "
    "objective, no curriculum) trained on the final images the agent has observed, its latents "
    "opened 2 at a time as the capacity grows, MGE exploration in its goal space with novelty "
    "steps, retrained (warm start, anchored) every --retrain-every episodes with the archive "
    "re-encoded. Kinematic arm by default. The defaults are the best measured configuration "
    "(docs/online.md). Exit: 0 done, 1 runtime failure, 2 usage error, 130/143 interrupted "
    "(continue with --resume).";

void print_line(const std::string& line) {
  fmt::print("{}\n", line);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  curio::online::CommandLine cl;
  CLI::App app{kDescription, "curio-online"};
  curio::online::add_options(app, cl);
  if (const auto code = curio::cli::parse(app, argc, argv)) return *code;
  curio::online::take_exploration_options(&cl);
  if (const std::string p = curio::online::command_line_problem(app, cl); !p.empty())
    return curio::cli::usage_error(app, p);
  OnlineOptions& o = cl.options;
  try {
    const fs::path opt_file = fs::path(o.out_dir) / "options.json";
    int rounds_done = 0;
    if (o.resume || cl.export_round >= 0) {
      std::ifstream f(opt_file);
      if (!f) return curio::cli::usage_error(app, fmt::format("--out: {} not found (no run there)", opt_file.string()));
      const nlohmann::json j = nlohmann::json::parse(f);
      if (const std::string p = curio::online::removed_option_in(j); !p.empty())
        return curio::cli::usage_error(app, fmt::format("--out: {}: {}", o.out_dir, p));
      OnlineOptions saved = curio::online::options_from_json(j);
      saved.out_dir = o.out_dir;
      saved.resume = o.resume;
      saved.threads = o.threads;
      saved.quiet = o.quiet;
      saved.stop_after_retrain = o.stop_after_retrain;
      o = saved;
    } else if (fs::exists(opt_file)) {
      return curio::cli::usage_error(
          app, fmt::format("--out: {} exists: pass --resume to continue that run, or choose another --out",
                           opt_file.string()));
    }
    if (const std::string p = curio::online::check(o); !p.empty()) return curio::cli::usage_error(app, p);
    torch::set_num_threads(o.threads);
    if (cl.export_round >= 0) {
      fmt::print("wrote {}\n", curio::online::export_codes(o, cl.export_round));
      return 0;
    }
    if (o.resume) {
      rounds_done = static_cast<int>(curio::online::load_state(o.out_dir).scene_hashes.size());
      if (!o.quiet)
        fmt::print("resuming {}: {} rounds done (replaying the exploration up to there)\n", o.out_dir, rounds_done);
    }
    // Flush denormal floats to zero on this thread (which runs the training at --threads 1).
    // As the decoder grows confident, background logits reach ≈ −90 and the BCE's exp() and
    // sigmoid() produce denormals that the CPU handles ~100× slower: training fell from ≈ 5 to
    // ≈ 3 it/s as a run went on. Measured on a round-4 retrain (4,400 images, 300 iterations,
    // two runs sharing two cores): 2.9 it/s flushed against 1.7 it/s, with bit-identical
    // weights (only Adam moments of order 1e-40, far below its ε, differ).
    at::globalContext().setFlushDenormal(true);
    const auto claim = curio::host::claim_output_folder_or_say("curio-online", o.out_dir,
                                                               curio::host::OutputAccess::kExclusive);
    if (!claim) return curio::cli::kRuntimeFailure;
    std::string write_error;
    if (!o.resume && !curio::host::write_file_atomically(
                         opt_file.string(), curio::online::to_json(o).dump(2) + "\n", &write_error)) {
      fmt::print(stderr, "curio-online: {}\n", write_error);
      return curio::cli::kRuntimeFailure;
    }
    if (!o.quiet) {
      fmt::print("curio-online: seed {}, {} + {} episodes, {} arm, retrains at episodes", o.seed, o.bootstrap,
                 o.episodes, curio::sim::physics_name(o.physics));
      for (int p : o.retrain_points()) fmt::print(" {}", p);
      fmt::print("\n");
    }
    const auto r = curio::online::run_online(o, rounds_done, o.quiet ? curio::online::ProgressFn{} : print_line);
    if (r.stopped) {
      fmt::print("stopped after round {} (--stop-after-retrain); continue with --resume\n", o.stop_after_retrain);
      return 0;
    }
    curio::online::write_final_report(o, r);
    // ratio_at_9666 is -1 in summary.json when the run is shorter than 9,666 episodes.
    const double at_9666 =
        nlohmann::json::parse(std::ifstream(fs::path(o.out_dir) / "summary.json"))["ratio_at_9666"].get<double>();
    fmt::print("done: ratio at 9666 {} (final {:.3f}) | verdict {} | ball latents {} | {} | archive {:08x} | {:.0f} s\n",
               at_9666 < 0 ? std::string("n/a (shorter run)") : fmt::format("{:.3f}", at_9666),
               r.ratio.empty() ? 0.0 : r.ratio.back(), curio::online::latents_text(r.verdict_latents),
               curio::online::latents_text(r.ball_latents), r.verdict_matches ? "MATCH" : "no match",
               r.archive_checksum, r.seconds);
    return 0;
  } catch (const std::exception& e) {
    fmt::print(stderr, "curio-online: error: {}\n", e.what());
    return curio::cli::kRuntimeFailure;
  }
}
