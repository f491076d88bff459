// curio-online: exploration with a goal space learned online from the agent's own images
// (issue 17; online_run.hpp says what a run does, online_state.hpp what it writes).
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <torch/torch.h>

#include "host_tools/online/online_options.hpp"
#include "host_tools/online/online_report.hpp"
#include "host_tools/online/online_run.hpp"
#include "host_tools/online/online_state.hpp"

namespace fs = std::filesystem;
using curio::online::OnlineOptions;

int main(int argc, char** argv) {
  OnlineOptions o;
  CLI::App app{
      "curio-online: random bootstrap, then a beta-VAE trained on the final images the agent has "
      "observed (SPEC §3 network and the shipped recipe's objective, no curriculum), goal modules "
      "from its latents' KL, MGE exploration in that goal space, retrained (warm start) every "
      "--retrain-every episodes with the archive re-encoded. Kinematic arm by default."};
  // A text option that takes one of `values` (CLI11 refuses anything else with the list).
  const auto add_choice = [&app](const std::string& name, std::string& field, const std::string& help,
                                 const std::vector<std::string>& values) {
    app.add_option(name, field, help)->check(CLI::IsMember(values))->capture_default_str();
  };
  app.add_option("--out", o.out_dir, "Output folder (checkpoints, reports, figures)")->capture_default_str();
  app.add_flag("--resume", o.resume,
               "Continue the run in --out from its last checkpoint (its options.json governs; "
               "only --threads and --stop-after-retrain may change)");
  app.add_option("--seed", o.seed, "Run seed (explorer, world, training)")->capture_default_str();
  app.add_option("--physics", o.physics, "Arm simulation: kinematic or ode")->capture_default_str();
  app.add_option("--sigma", o.sigma, "Explore noise σ on θ")->capture_default_str();
  app.add_option("--bootstrap", o.bootstrap, "Random episodes before the first training")->capture_default_str();
  app.add_option("--episodes", o.episodes, "Episodes after the bootstrap (multiple of 5)")->capture_default_str();
  app.add_option("--group-size", o.group_size, "Latents per goal module (2: MGE-βVAE's five pairs)")->capture_default_str();
  app.add_option("--competence-cap", o.competence_cap, "D of SPEC §2.5")->capture_default_str();
  app.add_option("--retrain-every", o.retrain_every, "Episodes between retrains (multiple of 5; 0: train once)")->capture_default_str();
  app.add_option("--last-retrain", o.last_retrain,
                 "No retrain after this episode count (the final goal space then stays fixed, "
                 "and the final verdict judges the episodes since)")->capture_default_str();
  app.add_option("--first-iterations", o.first_iterations, "Training iterations at the end of the bootstrap")->capture_default_str();
  app.add_option("--retrain-iterations", o.retrain_iterations, "Training iterations at each retrain (warm start)")->capture_default_str();
  app.add_option("--beta", o.beta, "β of the capacity term β·|KL − C| (see --kl-penalty)")->capture_default_str();
  add_choice("--kl-penalty", o.kl_penalty,
             "Capacity term: abs, β·|KL − C| (the recipe's: KL is held at C), or hinge, "
             "β·max(0, KL − C) (C is only a ceiling)",
             {"abs", "hinge"});
  app.add_option("--kl-weight", o.kl_weight,
                 "γ of an extra γ·KL term (a plain β-VAE price per nat beneath the capacity term; "
                 "with --kl-penalty hinge a latent then carries only what gains more than γ nats of "
                 "BCE per nat; 0: none)")->capture_default_str();
  add_choice("--decoder", o.decoder,
             "Decoder of the training: spec (SPEC §3's) or additive (the same network on each "
             "open latent group alone, their changes summed, so a group draws only what it holds "
             "itself); the encoder, the goal space, is SPEC §3's either way",
             {"spec", "additive"});
  app.add_option("--capacity-max", o.capacity_max, "C at the end of its ramp (nats)")->capture_default_str();
  app.add_option("--capacity-iters", o.capacity_iters,
                 "Iterations (over all trainings of the run) for C to rise 0 → --capacity-max")->capture_default_str();
  app.add_option("--batch", o.batch, "Training batch")->capture_default_str();
  app.add_option("--lr", o.lr, "Adam learning rate")->capture_default_str();
  app.add_option("--out-init-scale", o.out_init_scale, "enc.fc_out weights × this at init (KL ≈ 0 at the start)")->capture_default_str();
  app.add_option("--nats-per-latent", o.nats_per_latent,
                 "Progressive latents: a training uses only as many latents (in groups of "
                 "--group-size, opened in index order) as C at its end needs at this many nats each; "
                 "the rest are held at the prior, and the goal modules are the opened groups. "
                 "0: all ten latents from the start")->capture_default_str();
  app.add_option("--release-scale", o.release_scale,
                 "Progressive latents: a group opened at a retrain starts with read-out weights × this "
                 "(the first groups use --out-init-scale)")->capture_default_str();
  app.add_option("--surprise-fraction", o.surprise_fraction,
                 "Surprise sampling: at each retrain, this fraction of every batch is drawn from the "
                 "--surprise-top images the model reconstructs worst before the retrain (0: uniform batches)")->capture_default_str();
  app.add_option("--surprise-top", o.surprise_top,
                 "Surprise sampling: the fraction of the images, worst reconstructed first, it draws from")->capture_default_str();
  app.add_option("--skew-alpha", o.skew_alpha,
                 "Density-skewed batches (after Skew-Fit): at each retrain, images are drawn with "
                 "probability ∝ (k-NN density of their code in the open modules)^α, so the code is "
                 "learned from data flattened toward uniform over what was reached (α < 0, e.g. -1; 0: "
                 "uniform batches)")->capture_default_str();
  app.add_option("--skew-neighbours", o.skew_neighbours,
                 "Density-skewed batches: k of the k-NN density")->capture_default_str();
  app.add_option("--skew-cap", o.skew_cap,
                 "Density-skewed batches: no image weighs more than this × the mean")->capture_default_str();
  app.add_option("--novelty-fraction", o.novelty_fraction,
                 "Novelty steps: the share of goal-exploration steps (after the first training) that "
                 "explore around an archived episode whose image the model reconstructs worst, "
                 "instead of around the nearest neighbour of a goal (0: off)")->capture_default_str();
  app.add_option("--novelty-top", o.novelty_top,
                 "Novelty steps: the fraction of the archive, worst reconstructed first, a novelty "
                 "step draws its episode from")->capture_default_str();
  app.add_option("--anchor-weight", o.anchor_weight,
                 "Anchoring (progressive latents): a training that opens new latents adds this × "
                 "KL(new code ‖ code before the training) of the latents already open, so new content "
                 "goes to the new latents (0: off)")->capture_default_str();
  add_choice("--goal-modules", o.goal_modules,
             "Goal modules after each training: groups (every latent, in groups of --group-size), "
             "open-groups (progressive latents: the opened groups only) or open-singles "
             "(progressive latents: one module per open latent)",
             {"groups", "open-groups", "open-singles"});
  app.add_option("--goal-scale", o.goal_scale,
                 "Goals are this × clip(N(0, I), ±2.5) in each module (1: SPEC §2.3's prior; > 1 asks "
                 "beyond what the agent has reached, which the prior of a model trained on its own "
                 "images covers)")->capture_default_str();
  app.add_flag("--unmix", o.unmix, "FastICA-unmix the active latents after each training (images only)");
  app.add_option("--eval-images", o.eval_images,
                 "Held-out uniform scenes for the factor report after each training (evaluation only)")->capture_default_str();
  app.add_option("--interest-every", o.interest_every, "Episodes between interest samples")->capture_default_str();
  app.add_option("--progress-every", o.progress_every, "Episodes between progress lines")->capture_default_str();
  int export_round = -1;
  app.add_option("--export-codes", export_round,
                 "Analysis: write <out>/codes_round_R.csv, the μ round R's model gives every scene of the "
                 "run in --out (with the true positions, evaluation only), and exit")
      ->check(CLI::NonNegativeNumber);
  bool no_baselines = false;
  app.add_flag("--no-baselines", no_baselines, "Skip the passive MGE-βVAE and RPE runs at the end");
  app.add_option("--threads", o.threads, "LibTorch and rendering threads (results are bit-exact per thread count)")->capture_default_str();
  app.add_option("--stop-after-retrain", o.stop_after_retrain,
                 "Stop after this round's checkpoint, as if killed (tests; -1: never)")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  o.baselines = !no_baselines;

  try {
    const fs::path opt_file = fs::path(o.out_dir) / "options.json";
    int rounds_done = 0;
    if (o.resume || export_round >= 0) {
      std::ifstream f(opt_file);
      if (!f) {
        fmt::print(stderr, "error: {}: {} not found (no run there)\n", o.resume ? "--resume" : "--export-codes",
                   opt_file.string());
        return 2;
      }
      OnlineOptions saved = curio::online::options_from_json(nlohmann::json::parse(f));
      saved.out_dir = o.out_dir;
      saved.threads = o.threads;
      saved.stop_after_retrain = o.stop_after_retrain;
      saved.resume = o.resume;
      o = saved;
      if (export_round >= 0) {
        torch::set_num_threads(o.threads);
        fmt::print("wrote {}\n", curio::online::export_codes(o, export_round));
        return 0;
      }
      rounds_done = static_cast<int>(curio::online::load_state(o.out_dir).scene_hashes.size());
      fmt::print("resuming {}: {} rounds done (replaying the exploration up to there)\n", o.out_dir, rounds_done);
    } else {
      if (fs::exists(opt_file)) {
        fmt::print(stderr, "error: {} exists: pass --resume to continue that run, or choose another --out\n",
                   opt_file.string());
        return 2;
      }
    }
    if (const auto problems = curio::online::check(o); !problems.empty()) {
      for (const auto& p : problems) fmt::print(stderr, "error: {}\n", p);
      return 2;
    }
    torch::set_num_threads(o.threads);
    // Flush denormal floats to zero on this thread (which runs the training at --threads 1).
    // As the decoder grows confident, background logits reach ≈ −90 and the BCE's exp() and
    // sigmoid() produce denormals that the CPU handles ~100× slower: training fell from ≈ 5 to
    // ≈ 3 it/s as a run went on. Measured on a round-4 retrain (4,400 images, 300 iterations,
    // two runs sharing two cores): 2.9 it/s flushed against 1.7 it/s, with bit-identical
    // weights (only Adam moments of order 1e-40, far below its ε, differ).
    at::globalContext().setFlushDenormal(true);
    fs::create_directories(o.out_dir);
    if (!o.resume) std::ofstream(opt_file) << curio::online::to_json(o).dump(2) << "\n";
    fmt::print("curio-online: seed {}, {} + {} episodes, {} arm, retrains at episodes", o.seed, o.bootstrap,
               o.episodes, o.physics);
    for (int p : o.retrain_points()) fmt::print(" {}", p);
    fmt::print("\n");
    const auto r = curio::online::run_online(o, rounds_done, [](const std::string& line) {
      fmt::print("{}\n", line);
      std::fflush(stdout);
    });
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
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  }
}
