#include "host_tools/online/online_report.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host_tools/common/atomic_file.hpp"
#include "host_tools/common/gnuplot.hpp"
#include "host_tools/experiment/algorithms.hpp"
#include "host_tools/experiment/explore_strategies.hpp"
#include "host_tools/experiment/simulated_run.hpp"
#include "host_tools/online/online_state.hpp"
#include "host_tools/vae/scene_set.hpp"
#include "sim/world.hpp"

namespace curio::online {
namespace {

namespace fs = std::filesystem;

// A passive baseline's ratio curve at r.checkpoints, or empty with a warning.
std::vector<double> baseline_curve(const OnlineOptions& o, const std::string& algorithm) {
  const auto algo = lab::find_algorithm(algorithm);
  if (!algo) return {};
  lab::RunSpec spec;
  spec.algorithm = *algo;
  spec.explorer.seed = o.seed;
  spec.explorer.sigma = static_cast<float>(o.sigma);
  spec.explorer.n_bootstrap = o.bootstrap;
  spec.explorer.n_episodes = o.episodes;
  spec.explorer.competence_cap = static_cast<float>(algo->default_competence_clip);
  spec.physics = o.physics;
  // The passive goal space explores with the same strategy (as curio-lab --explore runs every
  // algorithm of a campaign), so the gap to it is the learned goal space's alone.
  if (const auto strategy = lab::find_explore_strategy(o.explore))
    lab::apply_explore_strategy(*strategy, &spec.explorer);
  const lab::RunResult res = lab::run_exploration(spec);
  if (!res.error.empty()) {
    fmt::print(stderr, "warning: baseline {}: {}\n", algorithm, res.error);
    return {};
  }
  return res.ratio;
}

double at_episode(const std::vector<int>& n, const std::vector<double>& v, int episode) {
  for (size_t i = 0; i < n.size() && i < v.size(); ++i)
    if (n[i] == episode) return v[i];
  return -1.0;
}

// A figure that cannot be written (a full disk, a gnuplot error) fails the report like any
// other file; only a machine without gnuplot gets a warning (the script is kept).
void figure(const fs::path& dir, const std::string& name, const std::string& script) {
  std::string err;
  bool not_installed = false;
  if (host::run_gnuplot((dir / (name + ".gp")).string(), script, &err, &not_installed)) return;
  if (!not_installed) throw std::runtime_error(err);
  fmt::print(stderr, "warning: {}.png: {}\n", name, err);
}


}  // namespace

void write_final_report(const OnlineOptions& o, const OnlineResult& r) {
  const fs::path dir = o.out_dir;
  std::vector<double> mge, rpe;
  if (o.baselines) {
    mge = baseline_curve(o, "MGE-βVAE");
    rpe = baseline_curve(o, "RPE");
  }
  {
    std::ostringstream f;
    f << "episodes,online" << (mge.empty() ? "" : ",mge_beta_vae_passive") << (rpe.empty() ? "" : ",rpe") << "\n";
    for (size_t i = 0; i < r.checkpoints.size() && i < r.ratio.size(); ++i) {
      f << r.checkpoints[i] << "," << fmt::format("{:.6f}", r.ratio[i]);
      if (!mge.empty()) f << "," << fmt::format("{:.6f}", mge[i]);
      if (!rpe.empty()) f << "," << fmt::format("{:.6f}", rpe[i]);
      f << "\n";
    }
    host::write_file_atomically_or_throw((dir / "curves.csv").string(), f.str());
  }
  {
    std::ostringstream f;
    f << "episodes";
    for (int k = 0; k < 10; ++k) f << ",slot" << k;
    f << "\n";
    for (size_t s = 0; s < r.interest_episodes.size(); ++s) {
      f << r.interest_episodes[s];
      for (float v : r.interest[s]) f << "," << fmt::format("{:.6g}", v);
      f << "\n";
    }
    host::write_file_atomically_or_throw((dir / "interest.csv").string(), f.str());
  }
  {
    std::ostringstream f;
    f << "round,episode,latent,kl_agent_images,corr_ball_x,corr_ball_y,corr_distractor_x,corr_distractor_y\n";
    for (const auto& rec : r.retrains)
      for (int l = 0; l < 10; ++l) {
        const auto& c = rec.corr[static_cast<size_t>(l)];
        f << fmt::format("{},{},{},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f}\n", rec.round, rec.episode, l,
                         rec.kl[static_cast<size_t>(l)], std::abs(c[0]), std::abs(c[1]),
                         std::abs(c[2]), std::abs(c[3]));
      }
    host::write_file_atomically_or_throw((dir / "latents.csv").string(), f.str());
  }
  const int n_eval = 9666;
  nlohmann::json s;
  s["seed"] = o.seed;
  s["episodes_total"] = o.bootstrap + o.episodes;
  s["ratio_final"] = r.ratio.empty() ? 0.0 : r.ratio.back();
  s["ratio_at_9666"] = at_episode(r.checkpoints, r.ratio, n_eval);
  s["passive_mge_beta_vae_ratio_at_9666"] = at_episode(r.checkpoints, mge, n_eval);
  s["rpe_ratio_at_9666"] = at_episode(r.checkpoints, rpe, n_eval);
  s["grasps"] = r.grasps;
  s["rebases"] = r.rebases;
  {
    // Evaluation only (true positions): how often each kind of episode moved the ball.
    int moved[2] = {0, 0}, count[2] = {0, 0};
    for (size_t i = static_cast<size_t>(o.bootstrap); i < r.scenes.size() && i < r.novelty_episode.size(); ++i) {
      const int k = r.novelty_episode[i];
      ++count[k];
      moved[k] += ball_moved(r.scenes[i]) ? 1 : 0;
    }
    s["novelty_steps"] = r.novelty_steps;
    s["ball_moved_share_novelty_episodes"] = count[1] ? static_cast<double>(moved[1]) / count[1] : 0.0;
    s["ball_moved_share_goal_episodes"] = count[0] ? static_cast<double>(moved[0]) / count[0] : 0.0;
    s["ball_moved_share_all"] =
        count[0] + count[1] ? static_cast<double>(moved[0] + moved[1]) / (count[0] + count[1]) : 0.0;
  }
  s["rounds"] = r.retrains.size();
  s["final_modules"] = r.final_modules;
  s["verdict_latents"] = r.verdict_latents;
  s["final_verdicts"] = nlohmann::json::array();  // per final module: why it is (not) controllable
  for (const auto& v : r.final_verdicts) s["final_verdicts"].push_back(verdict_json(v));
  s["ball_latents_final_model"] = r.ball_latents;
  s["verdict_names_ball_latents"] = r.verdict_matches;
  s["ball_latents_final_model_own_images"] = r.own_ball_latents;
  s["verdict_names_own_image_ball_latents"] = r.verdict_matches_own;
  s["verdict_text"] = latents_text(r.verdict_latents);
  s["archive_checksum"] = fmt::format("{:08x}", r.archive_checksum);
  s["wall_seconds_this_process"] = r.seconds;
  s["cpu_seconds_this_process"] = r.cpu_seconds;  // unlike wall time, not inflated by pauses or a busy machine
  double train_s = 0.0;
  for (const auto& rec : r.retrains) train_s += rec.training.seconds;
  s["training_seconds_all_rounds"] = train_s;
  host::write_file_atomically_or_throw((dir / "summary.json").string(), s.dump(2) + "\n");

  const std::string csv = host::gnuplot_quote((dir / "curves.csv").string());
  std::string plot = fmt::format(
      "set terminal pngcairo size 900,600\nset output {}\nset datafile separator ','\n"
      "set key top left\nset xlabel 'episodes'\nset ylabel 'exploration ratio'\n"
      "set title 'online MGE-βVAE (seed {}) vs passive baselines'\nplot {} using 1:2 with lines lw 2 title 'online'",
      host::gnuplot_quote((dir / "ratio.png").string()), o.seed, csv);
  if (!mge.empty()) plot += fmt::format(", {} using 1:3 with lines title 'MGE-βVAE (passive model)'", csv);
  if (!rpe.empty()) plot += fmt::format(", {} using 1:{} with lines title 'RPE'", csv, mge.empty() ? 3 : 4);
  figure(dir, "ratio", plot + "\n");

  std::string arrows;
  for (const auto& rec : r.retrains)
    arrows += fmt::format("set arrow from {0},graph 0 to {0},graph 1 nohead dt 2 lc rgb 'gray'\n", rec.episode);
  std::string iplot = fmt::format(
      "set terminal pngcairo size 900,600\nset output {}\nset datafile separator ','\n"
      "set key outside right\nset xlabel 'episodes (dashed: retrains)'\nset ylabel 'interest |cp|'\n"
      "set title 'interest of each module slot (slot k = k-th module by KL)'\n{}plot ",
      host::gnuplot_quote((dir / "interest.png").string()), arrows);
  const int slots = 10 / o.group_size;
  for (int k = 0; k < slots; ++k)
    iplot += fmt::format("{}{} using 1:{} with lines title 'slot {}'", k ? ", " : "",
                         host::gnuplot_quote((dir / "interest.csv").string()), k + 2, k);
  figure(dir, "interest", iplot + "\n");

  const std::string lcsv = host::gnuplot_quote((dir / "latents.csv").string());
  std::string lplot = fmt::format(
      "set terminal pngcairo size 1500,650\nset output {}\nset datafile separator ','\n"
      "set multiplot layout 2,5 title 'each latent across retrains: |corr| with the true factors "
      "(held-out, evaluation only) and KL/12 on the agent images'\nset yrange [0:1]\nset key off\nset xtics 3000\n",
      host::gnuplot_quote((dir / "latents.png").string()));
  for (int l = 0; l < 10; ++l) {
    lplot += fmt::format("set title 'z{}'\nset xlabel 'episode'\n", l);
    if (l == 0) lplot += "set key top left font ',8'\n";
    lplot += fmt::format(
        "plot {0} using ($3=={1}?$2:1/0):5 with linespoints title 'ball x', "
        "{0} using ($3=={1}?$2:1/0):6 with linespoints title 'ball y', "
        "{0} using ($3=={1}?$2:1/0):7 with linespoints title 'distr x', "
        "{0} using ($3=={1}?$2:1/0):8 with linespoints title 'distr y', "
        "{0} using ($3=={1}?$2:1/0):($4/12) with points pt 6 lc rgb 'black' title 'KL/12'\n",
        lcsv, l);
    if (l == 0) lplot += "set key off\n";
  }
  figure(dir, "latents", lplot + "unset multiplot\n");
}

std::string export_codes(const OnlineOptions& o, int round) {
  const fs::path dir(o.out_dir);
  const std::string model = round_model_path(o.out_dir, round);
  if (!fs::exists(model)) throw std::runtime_error(model + " not found (no such round in this run)");
  const train::SceneSet scenes = train::load_scene_set_csv((dir / "scenes.csv").string(), o.threads);
  OnlineVae vae(o);
  vae.load(model);
  const EncodedScenes enc = encode_images(vae.model(), scenes.images);
  const auto f = scenes.factors.contiguous();
  const float* pf = f.data_ptr<float>();
  std::string text = "episode,ball_x,ball_y,distractor_x,distractor_y";
  for (int l = 0; l < 10; ++l) text += fmt::format(",mu{}", l);
  text += "\n";
  const int64_t n = scenes.images.size(0);
  for (int64_t i = 0; i < n; ++i) {
    text += fmt::format("{},{:.9g},{:.9g},{:.9g},{:.9g}", i, pf[i * 4], pf[i * 4 + 1], pf[i * 4 + 2], pf[i * 4 + 3]);
    for (int l = 0; l < 10; ++l) text += fmt::format(",{:.6g}", enc.mu[static_cast<size_t>(i * 10 + l)]);
    text += "\n";
  }
  const fs::path out = dir / fmt::format("codes_round_{}.csv", round);
  host::write_file_atomically_or_throw(out.string(), text);
  return out.string();
}

}  // namespace curio::online
