#include "host_tools/online/online_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>

#include "firmware/explore/fnv1a.hpp"
#include "firmware/explore/schedule.hpp"
#include "host_tools/experiment/checkpoints.hpp"
#include "host_tools/experiment/exploration_ratio.hpp"
#include "host_tools/experiment/explore_strategies.hpp"
#include "host_tools/online/online_state.hpp"
#include "host_tools/vae/evaluate.hpp"
#include "host_tools/vae/scene_set.hpp"
#include "sim/world.hpp"

namespace curio::online {
namespace {

namespace fs = std::filesystem;

constexpr uint64_t kNoveltyStream = 2000;  // Prng stream of the novelty-step draws

ExplorerConfig base_config(const OnlineOptions& o) {
  ExplorerConfig c;
  c.seed = o.seed;
  c.sigma = static_cast<float>(o.sigma);
  c.competence_cap = static_cast<float>(o.competence_cap);
  c.n_bootstrap = o.bootstrap;
  c.n_episodes = o.episodes;
  if (const auto strategy = lab::find_explore_strategy(o.explore)) lab::apply_explore_strategy(*strategy, &c);
  // Before the first training the modules are placeholders (identity order): bootstrap
  // episodes are random and their outcomes are rewritten by the first rebase.
  std::array<uint8_t, 10> identity{};
  for (uint8_t i = 0; i < 10; ++i) identity[i] = i;
  return goal_space_config(c, identity, o.group_size);
}

uint32_t hash_scenes(const std::vector<Scene>& scenes) {
  Fnv1a h;
  for (const Scene& s : scenes)
    for (float v : s) h.add_float(v);
  return h.h;
}

// Latents whose best factor is one of `factors` (active, |corr| ≥ .5), as the lab reads the
// shipped model's report (lab::ball_latents).
std::vector<int> latents_of(const train::FactorReport& r, int f0, int f1) {
  std::vector<int> out;
  for (int l : r.active) {
    const int f = r.best_factor[static_cast<size_t>(l)];
    if ((f == f0 || f == f1) && std::abs(r.corr[static_cast<size_t>(l)][static_cast<size_t>(f)]) >= 0.5)
      out.push_back(l);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Controllable-feature verdict of the episodes (begin, end] (counts, as lab::RunRecorder) run with `modules`.
void judge_segment(const OnlineResult& r, int begin, int end, const std::vector<std::vector<int>>& modules,
                   std::vector<lab::ModuleVerdict>* verdicts, std::vector<int>* latents) {
  std::vector<lab::ProgressSample> ex;
  for (const auto& p : r.exploits)
    if (p.episode > begin && p.episode <= end) ex.push_back(p);
  std::vector<std::vector<float>> interest;
  std::vector<int> at;
  for (size_t s = 0; s < r.interest_episodes.size(); ++s)
    if (r.interest_episodes[s] > begin && r.interest_episodes[s] <= end) {
      at.push_back(r.interest_episodes[s]);
      interest.emplace_back(r.interest[s].begin(),
                            r.interest[s].begin() + static_cast<std::ptrdiff_t>(modules.size()));
    }
  *verdicts = lab::classify_modules(ex, interest, at, begin, end);
  *latents = lab::controllable_latents(*verdicts, modules);
  std::sort(latents->begin(), latents->end());
}

class OnlineRun {
 public:
  OnlineRun(const OnlineOptions& o, int rounds_done, const ProgressFn& progress)
      : o_(o), rounds_done_(rounds_done), progress_(progress), vae_(o) {
    points_ = o.retrain_points();
    explorer_ = std::make_unique<Explorer>();
    config_ = base_config(o);
    if (explorer_->init(config_) != Status::kOk) throw std::runtime_error("explorer init failed");
    world_ = sim::make_world(o.physics, sim::WorldParams{}, sim::world_seed_for_run(o.seed));
    heldout_ = train::render_scene_set(o.eval_images, o.seed, train::kReportStream, o.threads);
    r_.checkpoints = lab::curve_checkpoints(explorer_->total_episodes());
    state_ = load_state(o.out_dir);
    if (rounds_done_ > static_cast<int>(state_.scene_hashes.size()))
      throw std::runtime_error("state.json records fewer rounds than asked to resume");
  }

  OnlineResult run() {
    const auto t0 = std::chrono::steady_clock::now();
    float theta[kThetaDim];
    float outcome[kMaxOutcomeDim] = {};
    size_t next_point = 0;
    const int total = explorer_->total_episodes();
    while (next_checkpoint_ < r_.checkpoints.size() && r_.checkpoints[next_checkpoint_] == 0) {
      r_.ratio.push_back(0.0);
      ++next_checkpoint_;
    }
    while (!explorer_->done()) {
      const int e = explorer_->episode();
      if (next_point < points_.size() && e == points_[next_point]) {
        retrain(static_cast<int>(next_point));
        ++next_point;
        if (r_.stopped) return finish(t0);
      }
      maybe_novelty_step();
      if (explorer_->propose(theta) != Status::kOk) throw std::runtime_error("propose failed");
      const EpisodeKind kind = explorer_->kind();
      const sim::SceneState s = world_->rollout_joint_targets(theta);
      const Scene scene{static_cast<float>(s.ball.x), static_cast<float>(s.ball.y),
                        static_cast<float>(s.distractor.x), static_cast<float>(s.distractor.y)};
      double bce = 0.0;
      if (trained_) encode_scene(vae_.model(), scene, outcome, o_.novelty_fraction > 0.0 ? &bce : nullptr);
      surprise_.push_back(bce);
      if (const Status st = explorer_->observe(outcome); st != Status::kOk)
        throw std::runtime_error(std::string("observe failed: ") + to_string(st));
      r_.scenes.push_back(scene);
      // A novelty step's episodes are the goal-exploration episodes without a module.
      r_.novelty_episode.push_back(kind != EpisodeKind::kBootstrap && explorer_->module() < 0 ? 1 : 0);
      r_.grasps += s.grasped ? 1 : 0;
      metric_.add(scene[0], scene[1]);
      const int n = explorer_->episode();
      if (kind == EpisodeKind::kExploit && explorer_->module() >= 0)  // not a novelty step's
        r_.exploits.push_back({n, explorer_->module(), explorer_->last_progress()});
      if (n % o_.interest_every == 0 || n == total) {
        r_.interest_episodes.push_back(n);
        std::vector<float> v(kMaxModules, 0.0f);
        for (int k = 0; k < explorer_->n_modules(); ++k) v[static_cast<size_t>(k)] = explorer_->interest(k);
        r_.interest.push_back(v);
      }
      while (next_checkpoint_ < r_.checkpoints.size() && r_.checkpoints[next_checkpoint_] == n) {
        r_.ratio.push_back(metric_.ratio());
        ++next_checkpoint_;
      }
      if (n % o_.progress_every == 0 || n == total) {
        std::string in;
        for (int k = 0; k < explorer_->n_modules(); ++k) in += fmt::format(" {:.4f}", explorer_->interest(k));
        say(fmt::format("episode {}/{} | ratio {:.3f} | grasps {} | interest{}{} | {:.0f} s", n, total,
                        metric_.ratio(), r_.grasps, in,
                        o_.novelty_fraction > 0.0 ? fmt::format(" | novelty steps {}", r_.novelty_steps) : "",
                        seconds_since(t0)));
      }
    }
    // Final verdict: the segment since the last retrain, in the last goal space.
    r_.final_modules = module_latents(config_);
    judge_segment(r_, points_.back(), total, r_.final_modules, &r_.final_verdicts, &r_.verdict_latents);
    r_.ball_latents = r_.retrains.back().ball_latents;
    r_.verdict_matches = !r_.ball_latents.empty() && r_.verdict_latents == r_.ball_latents;
    r_.own_ball_latents = r_.retrains.back().own_ball_latents;
    r_.verdict_matches_own = !r_.own_ball_latents.empty() && r_.verdict_latents == r_.own_ball_latents;
    write_scenes_csv(o_.out_dir, r_.scenes);
    return finish(t0);
  }

 private:
  static double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  void say(const std::string& s) const {
    if (progress_) progress_(s);
  }

  // At the start of a goal-exploration step after the first training: with probability
  // novelty_fraction, direct the step to explore around one of the worst-reconstructed
  // episodes (ties: lower index).
  void maybe_novelty_step() {
    const int e = explorer_->episode();
    if (o_.novelty_fraction <= 0.0 || !trained_ || explorer_->kind() != EpisodeKind::kExplore ||
        (e - o_.bootstrap) % kEpisodesPerStep != 0)
      return;
    if (novelty_rng_.uniform01() >= o_.novelty_fraction) return;
    const auto k = std::max<size_t>(1, static_cast<size_t>(o_.novelty_top * e));
    std::vector<uint32_t> idx = worst_reconstructed(surprise_, k);
    std::sort(idx.begin(), idx.end());  // drawn by index order
    const auto pick = std::min(k - 1, static_cast<size_t>(novelty_rng_.uniform01() * static_cast<double>(k)));
    if (explorer_->explore_around(static_cast<int>(idx[pick])) != Status::kOk) throw std::runtime_error("explore_around failed");
    ++r_.novelty_steps;
  }

  OnlineResult finish(std::chrono::steady_clock::time_point t0) {
    Fnv1a h;
    h.add_archive(explorer_->archive());
    r_.archive_checksum = h.h;
    r_.seconds = seconds_since(t0);
    r_.cpu_seconds = static_cast<double>(std::clock() - cpu0_) / CLOCKS_PER_SEC;
    return std::move(r_);
  }

  void retrain(int round) {
    const int e = explorer_->episode();
    RetrainRecord rec;
    rec.round = round;
    rec.episode = e;
    rec.scenes_hash = hash_scenes(r_.scenes);
    if (round > 0) {
      rec.segment_modules = module_latents(config_);
      judge_segment(r_, points_[static_cast<size_t>(round - 1)], e, rec.segment_modules,
                    &rec.segment_verdicts, &rec.segment_controllable);
    }
    const train::SceneSet own = scene_set_of(r_.scenes, o_.threads);
    const torch::Tensor& images = own.images;
    const std::string model_path = round_model_path(o_.out_dir, round);
    if (round < rounds_done_) {
      if (state_.scene_hashes[static_cast<size_t>(round)] != rec.scenes_hash)
        throw std::runtime_error(fmt::format(
            "resume: the replayed run saw other scenes before round {} than the checkpointed one "
            "(hash {:08x}, recorded {:08x}): a different binary or options?", round, rec.scenes_hash,
            state_.scene_hashes[static_cast<size_t>(round)]));
      vae_.load(model_path);
      rec.loaded = true;
      rec.training = state_.training[static_cast<size_t>(round)];
      say(fmt::format("round {} at episode {}: model loaded from {} (resume)", round, e, model_path));
    } else {
      const int64_t iters = round == 0 ? o_.first_iterations : o_.retrain_iterations;
      say(fmt::format("round {} at episode {}: training {} iterations on {} images", round, e, iters,
                      images.size(0)));
      rec.training = vae_.train(images, iters, round, progress_);
    }
    trained_ = true;
    const EncodedScenes enc = encode_images(vae_.model(), images, o_.novelty_fraction > 0.0);
    if (o_.novelty_fraction > 0.0) surprise_ = enc.recon;
    rec.kl = enc.kl;
    rec.kl_order = enc.kl_order;
    rec.mu_mean = enc.mu_mean;
    rec.mu_std = enc.mu_sd;
    // Progressive latents: the modules are the groups opened together (not the KL order,
    // which can pair a latent of one group with one of another).
    const std::array<uint8_t, 10> order =
        o_.progressive() ? group_order(enc.kl, o_.group_size) : enc.kl_order;
    const ExplorerConfig next = goal_space_config(config_, order, o_.group_size);
    rec.carried_cp = carried_progress(*explorer_, next);
    if (const Status s = explorer_->rebase(next, enc.mu.data(), rec.carried_cp.data()); s != Status::kOk)
      throw std::runtime_error(std::string("explorer rebase failed: ") + to_string(s));
    config_ = next;
    ++r_.rebases;
    rec.modules = module_latents(config_);
    // Evaluation only: the held-out uniform scenes and their true factors.
    double recon = 0.0;
    const train::FactorReport fr = train::evaluate_factors(vae_.model(), "beta-vae", heldout_, {}, &recon);
    rec.factor_report = train::to_json(fr);
    rec.corr = fr.corr;
    rec.factor_report["heldout_recon"] = recon;
    rec.ball_latents = latents_of(fr, 0, 1);
    rec.distractor_latents = latents_of(fr, 2, 3);
    double own_recon = 0.0;
    const train::FactorReport own_fr = train::evaluate_factors(vae_.model(), "beta-vae", own, {}, &own_recon);
    rec.own_factor_report = train::to_json(own_fr);
    rec.own_factor_report["recon"] = own_recon;
    rec.own_ball_latents = latents_of(own_fr, 0, 1);
    rec.own_distractor_latents = latents_of(own_fr, 2, 3);
    std::string kl;
    for (uint8_t l : enc.kl_order)
      if (enc.kl[l] > 0.5) kl += fmt::format(" z{} {:.2f}", l, enc.kl[l]);
    say(fmt::format("round {}: {} latents open | active KL{} | ball {} distractor {} | MIG {:.3f} | segment verdict {}",
                    round, rec.training.open_latents, kl.empty() ? " none" : kl, latents_text(rec.ball_latents),
                    latents_text(rec.distractor_latents), fr.mig_all.mig,
                    round > 0 ? latents_text(rec.segment_controllable) : "-"));
    {
      const int from = round > 0 ? points_[static_cast<size_t>(round - 1)] : 0;
      int moved = 0;
      for (int i = from; i < e; ++i) moved += ball_moved(r_.scenes[static_cast<size_t>(i)]) ? 1 : 0;
      say(fmt::format("round {}: episodes {}-{} moved the ball in {:.1f} % (evaluation only){}", round, from, e,
                      e > from ? 100.0 * moved / (e - from) : 0.0,
                      o_.novelty_fraction > 0.0 ? fmt::format(" | novelty steps so far {}", r_.novelty_steps) : ""));
    }
    say(fmt::format("round {}: on the agent's own images: ball {} distractor {} | MIG {:.3f} | recon {:.1f}",
                    round, latents_text(rec.own_ball_latents), latents_text(rec.own_distractor_latents),
                    own_fr.mig_all.mig, own_recon));
    r_.retrains.push_back(rec);
    write_retrain_json(o_.out_dir, rec);
    if (!rec.loaded) {
      vae_.save(model_path, images.size(0));
      write_scenes_csv(o_.out_dir, r_.scenes);
      state_.scene_hashes.resize(static_cast<size_t>(round));
      state_.training.resize(static_cast<size_t>(round));
      state_.scene_hashes.push_back(rec.scenes_hash);
      state_.training.push_back(rec.training);
      save_state(o_.out_dir, state_);
      say(fmt::format("round {}: checkpoint written ({} rounds done)", round, round + 1));
    }
    if (o_.stop_after_retrain == round) r_.stopped = true;
  }

  OnlineOptions o_;
  int rounds_done_;
  ProgressFn progress_;
  OnlineVae vae_;
  std::vector<int> points_;
  std::unique_ptr<Explorer> explorer_;
  ExplorerConfig config_;
  std::unique_ptr<sim::World> world_;
  train::SceneSet heldout_;
  RunState state_;
  OnlineResult r_;
  lab::ExplorationRatio metric_;
  size_t next_checkpoint_ = 0;
  bool trained_ = false;
  std::clock_t cpu0_ = std::clock();  // process CPU time when the run began
  std::vector<double> surprise_;  // per archived episode: BCE under the current model (novelty steps)
  Prng novelty_rng_{o_.seed, kNoveltyStream};
};

}  // namespace

std::string latents_text(const std::vector<int>& latents) {
  std::string s;
  for (int z : latents) s += fmt::format("{}z{}", s.empty() ? "" : ",", z);
  return s.empty() ? "none" : s;
}

OnlineResult run_online(const OnlineOptions& o, int rounds_done, const ProgressFn& progress) {
  OnlineRun run(o, rounds_done, progress);
  return run.run();
}

}  // namespace curio::online
