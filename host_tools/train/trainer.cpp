#include <array>
#include "host_tools/train/trainer.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>
#include <torch/torch.h>

#include "firmware/explore/prng.hpp"
#include "host_tools/train/blas_info.hpp"
#include "host_tools/train/checkpoint.hpp"
#include "host_tools/train/evaluate.hpp"
#include "host_tools/train/figures.hpp"
#include "host_tools/train/latent_unmixing.hpp"
#include "host_tools/train/scene_set.hpp"
#include "host_tools/train/vae_model.hpp"

namespace curio::train {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::atomic<bool> g_stop{false};
extern "C" void on_stop_signal(int) { g_stop = true; }

std::string format_duration(double seconds) {
  const auto s = static_cast<int64_t>(seconds < 0 ? 0 : seconds);
  return fmt::format("{}:{:02}:{:02}", s / 3600, (s / 60) % 60, s % 60);
}

// Shuffled passes over the data set without replacement; the permutation of pass e is a
// function of (seed, e) alone, so a resumed run draws the same batches.
class BatchSampler {
 public:
  BatchSampler(int64_t n, int64_t batch, uint64_t seed)
      : n_(n), batch_(batch), per_pass_(n / batch), seed_(seed) {}

  torch::Tensor indices(int64_t iteration) {
    const int64_t pass = iteration / per_pass_;
    if (pass != pass_) {
      perm_ = torch::arange(n_, torch::kInt64);
      int64_t* p = perm_.data_ptr<int64_t>();
      Prng rng(seed_ + 0x9E3779B97F4A7C15ULL * static_cast<uint64_t>(pass + 1), 11);
      for (int64_t i = n_ - 1; i > 0; --i)
        std::swap(p[i], p[rng.below(static_cast<uint32_t>(i + 1))]);
      pass_ = pass;
    }
    return perm_.narrow(0, (iteration % per_pass_) * batch_, batch_);
  }

 private:
  int64_t n_, batch_, per_pass_;
  uint64_t seed_;
  int64_t pass_ = -1;
  torch::Tensor perm_;
};

constexpr const char* kCsvHeader = "iteration,loss,recon,kl,beta,capacity,lr,it_per_s";

// Keeps the header and the rows up to `last_iteration` (what the checkpoint covers).
void truncate_csv(const std::string& path, int64_t last_iteration) {
  std::ifstream in(path);
  if (!in) return;
  std::string line, kept;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    if (!std::isdigit(static_cast<unsigned char>(line[0])) ||
        std::stoll(line.substr(0, line.find(','))) <= last_iteration)
      kept += line + "\n";
  }
  in.close();
  std::ofstream(path, std::ios::trunc) << kept;
}

void check_recipe(const Recipe& r) {
  if (r.model != "beta-vae" && r.model != "vae")
    throw std::runtime_error("--model must be beta-vae or vae, not '" + r.model + "'");
  if (r.iterations < 1 || r.batch < 1) throw std::runtime_error("--iterations and --batch must be ≥ 1");
  if (r.dataset_size < r.batch)
    throw std::runtime_error(
        fmt::format("--dataset-size {} is smaller than --batch {}", r.dataset_size, r.batch));
  if (!(r.lr > 0.0)) throw std::runtime_error("--lr must be > 0");
  if (!r.scenes_file.empty() && (r.ball_spread < 1.0 || r.ball_spread_iters > 0))
    throw std::runtime_error("--scenes trains on the file's scenes as they are: no --ball-spread");
}

void print_blas(int threads) {
  (void)torch::mm(torch::ones({8, 8}), torch::ones({8, 8}));  // maps the BLAS library
  const BlasInfo blas = detect_blas();
  fmt::print("BLAS: {} ({}); LibTorch threads: {}\n",
             blas.library.empty() ? "none mapped" : blas.library,
             blas.openblas ? "OpenBLAS" : blas.reference ? "reference BLAS: SLOW" : "unknown",
             threads);
  if (!blas.openblas)
    fmt::print(
        "warning: not running on OpenBLAS; training is 4-5x slower. Install "
        "libopenblas0-openmp and check update-alternatives --display "
        "libblas.so.3-x86_64-linux-gnu\n");
}

std::string kl_list(const std::vector<double>& kl) {
  std::string s;
  for (double v : kl) s += fmt::format("{}{:.2f}", s.empty() ? "" : " ", v);
  return s;
}

// Figures and factor report of a model on the held-out report set; returns the report.
FactorReport write_outputs(Vae& model, const Recipe& recipe, const std::string& dir,
                           int64_t images, int threads) {
  model->eval();
  const SceneSet set = render_scene_set(images, recipe.seed, kReportStream, threads);
  const FactorReport report = evaluate_factors(model, recipe.model, set);
  std::ofstream(fs::path(dir) / "factor_report.json") << to_json(report).dump(2) << "\n";

  std::vector<int> order(report.kl_per_latent.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return report.kl_per_latent[static_cast<size_t>(a)] > report.kl_per_latent[static_cast<size_t>(b)];
  });
  std::string err;
  const auto first = to_float(set.images.narrow(0, 0, std::min<int64_t>(8, images)));
  if (!write_traversal_png(model, first[0], order, (fs::path(dir) / "traversal.png").string(), &err))
    fmt::print(stderr, "warning: traversal.png: {}\n", err);
  if (!write_reconstruction_png(model, first, (fs::path(dir) / "reconstruction.png").string(), &err))
    fmt::print(stderr, "warning: reconstruction.png: {}\n", err);
  const auto csv = fs::path(dir) / "training.csv";
  if (fs::exists(csv) &&
      !write_kl_plot(csv.string(), (fs::path(dir) / "kl_per_latent.png").string(), &err))
    fmt::print(stderr, "warning: kl_per_latent.png: {}\n", err);
  return report;
}

// Brings the number of trained latents to `trained`: releases held latents (lowest index
// first) with fresh weights, or holds the trained latents of lowest `importance` (recent KL,
// or reconstruction cost with --prune-by recon). Returns whether anything changed.
bool update_held_latents(Vae& model, LatentMask& held, int trained,
                         const std::array<double, kLatents>& importance, double out_scale) {
  int now = 0;
  for (bool h : held) now += h ? 0 : 1;
  if (now == trained) return false;
  LatentMask change{};
  if (trained > now) {
    for (int l = 0, n = trained - now; l < kLatents && n > 0; ++l)
      if (held[static_cast<size_t>(l)]) change[static_cast<size_t>(l)] = true, --n;
    model->release_latents(change, out_scale);
    for (int l = 0; l < kLatents; ++l) held[static_cast<size_t>(l)] &= !change[static_cast<size_t>(l)];
  } else {
    std::vector<int> live;
    for (int l = 0; l < kLatents; ++l)
      if (!held[static_cast<size_t>(l)]) live.push_back(l);
    std::stable_sort(live.begin(), live.end(), [&](int a, int b) {
      return importance[static_cast<size_t>(a)] < importance[static_cast<size_t>(b)];
    });
    for (int i = 0; i < now - trained; ++i) held[static_cast<size_t>(live[static_cast<size_t>(i)])] = true;
    model->hold_latents(held);
  }
  return true;
}

}  // namespace

int run_training(const TrainOptions& o) {
  Recipe recipe = o.recipe;
  check_recipe(recipe);
  fs::create_directories(o.out_dir);
  const std::string ckpt = checkpoint_path(o.out_dir);
  const std::string csv_path = (fs::path(o.out_dir) / "training.csv").string();
  if (!o.resume && fs::exists(ckpt))
    throw std::runtime_error(ckpt + " exists: pass --resume to continue it, or choose another --out");

  torch::set_num_threads(o.threads);
  print_blas(torch::get_num_threads());
  torch::manual_seed(recipe.seed);
  Vae model;
  if (recipe.init == "kaiming")
    model->kaiming_init(recipe.out_init_scale);
  else
    model->scale_encoder_output(recipe.out_init_scale);
  if (!recipe.init_from.empty() && !(o.resume && fs::exists(ckpt))) {
    const CheckpointInfo from = load_checkpoint(recipe.init_from, model, nullptr);
    fmt::print("initialised from {} ({} at iteration {})\n", recipe.init_from, from.recipe.model,
               from.iteration);
  }
  LatentMask held{};
  if (recipe.init_from.empty()) {
    for (int l = trained_latents(recipe, 0); l < kLatents; ++l) held[static_cast<size_t>(l)] = true;
    model->hold_latents(held);
  } else {
    held = model->held_latents();  // stage 0 is applied by KL once the data exist
  }
  torch::optim::Adam optimizer(model->parameters(), torch::optim::AdamOptions(recipe.lr));

  int64_t start = 0;
  if (o.resume && fs::exists(ckpt)) {
    const CheckpointInfo info = load_checkpoint(ckpt, model, &optimizer);
    const int64_t wanted = recipe.iterations;
    recipe = info.recipe;  // the run's own recipe governs; only its length may change
    recipe.iterations = wanted;
    start = info.iteration;
    held = model->held_latents();
    truncate_csv(csv_path, start);
    fmt::print("resumed {} at iteration {} (recipe from the checkpoint, iterations {})\n", ckpt,
               start, recipe.iterations);
  } else {
    std::ofstream(csv_path, std::ios::trunc) << kCsvHeader << [] {
      std::string s;
      for (int l = 0; l < kLatents; ++l) s += fmt::format(",kl_z{}", l);
      return s;
    }() << "\n";
    fs::remove(fs::path(o.out_dir) / "eval.jsonl");
  }
  SceneSet scenes;  // --scenes: an exploration's own images, all of them
  if (!recipe.scenes_file.empty()) {
    scenes = load_scene_set_csv(recipe.scenes_file, o.threads);
    recipe.dataset_size = scenes.images.size(0);
    check_recipe(recipe);
  }
  std::ofstream(fs::path(o.out_dir) / "recipe.json") << to_json(recipe).dump(2) << "\n";
  fmt::print("recipe: {}\n", to_json(recipe).dump());

  auto t0 = Clock::now();
  double spread = schedule_at(recipe, start).ball_spread;
  if (spread < 1.0 || recipe.ball_spread_iters > 0)
    fmt::print("curriculum: training images draw the ball in [-{0}, {0}]^2, not SPEC §3's "
               "[-1, 1]^2{1}\n", spread,
               recipe.ball_spread_iters > 0
                   ? fmt::format(" (moving to {} by iteration {})", recipe.ball_spread_to,
                                 recipe.ball_spread_iters)
                   : std::string{});
  SceneSet data = recipe.scenes_file.empty()
                     ? render_scene_set(recipe.dataset_size, recipe.seed, kTrainStream, o.threads, spread)
                     : std::move(scenes);
  const SceneSet eval_set = o.eval_every > 0
                                ? render_scene_set(o.eval_images, recipe.seed, kEvalStream, o.threads)
                                : SceneSet{};
  fmt::print("rendered {} training + {} held-out images in {:.1f} s\n", recipe.dataset_size,
             o.eval_every > 0 ? o.eval_images : 0,
             std::chrono::duration<double>(Clock::now() - t0).count());

  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
  BatchSampler sampler(recipe.dataset_size, recipe.batch, recipe.seed);
  std::ofstream csv(csv_path, std::ios::app);
  double w_loss = 0, w_recon = 0, w_kl = 0;
  torch::Tensor w_kl_latent = torch::zeros({kLatents}, torch::kFloat64);
  int64_t w_n = 0;
  const auto run_start = Clock::now();
  auto window_start = run_start;

  if (recipe.freeze_active_readout && (recipe.init_from.empty() || start > 0))
    throw std::runtime_error("--freeze-active-readout needs --init-from and a fresh run (the "
                             "frozen latents are chosen from the initial model)");
  torch::Tensor frozen_rows, frozen_weight, frozen_bias;  // read-out rows held fixed
  std::array<double, kLatents> kl_ema{};
  if (!recipe.init_from.empty() && start == 0) {
    // An initialised model keeps its strongest latents when stage 0 trains fewer than it has.
    torch::NoGradGuard no_grad;
    const auto idx = torch::arange(std::min<int64_t>(512, recipe.dataset_size));
    auto [mu, logvar] = model->enc->forward(gather_images(data.images, idx));
    const auto k = kl_per_latent(mu, logvar).to(torch::kFloat64).contiguous();
    for (size_t l = 0; l < kl_ema.size(); ++l) kl_ema[l] = k.data_ptr<double>()[l];
    if (recipe.freeze_active_readout) {
      std::vector<int64_t> rows;
      std::string which;
      for (int l = 0; l < kLatents; ++l)
        if (kl_ema[static_cast<size_t>(l)] > 0.5) {
          rows.push_back(l);
          rows.push_back(l + kLatents);
          which += fmt::format(" z{}", l);
        }
      frozen_rows = torch::tensor(rows, torch::kInt64);
      frozen_weight = model->enc->fc_out->weight.index_select(0, frozen_rows).clone();
      frozen_bias = model->enc->fc_out->bias.index_select(0, frozen_rows).clone();
      fmt::print("it 0: read-out of the active latents{} held fixed\n", which);
    }
    if (update_held_latents(model, held, trained_latents(recipe, 0), kl_ema, recipe.out_init_scale))
      fmt::print("it 0: {} latents train (lowest-KL latents of the initial model held)\n",
                 trained_latents(recipe, 0));
  }
  model->train();
  for (int64_t it = start; it < recipe.iterations; ++it) {
    if (recipe.reinit_after_warmup && recipe.warmup > 0 && it == recipe.warmup) {
      if (recipe.reinit_decoder) {
        model->reinit_decoder(recipe.out_init_scale);
        for (const auto& p : model->dec->parameters())
          optimizer.state().erase(c10::guts::to_string(p.unsafeGetTensorImpl()));
      } else {
        model->reinit_latent_layers(recipe.out_init_scale);
      }
      for (auto* layer : {&model->enc->fc_out, &model->dec->fc1})
        for (const auto& p : (*layer)->parameters())
          optimizer.state().erase(c10::guts::to_string(p.unsafeGetTensorImpl()));
      fmt::print("it {}: warm-up done; re-initialised enc.fc_out and dec.fc1\n", it);
    }
    const ScheduleAt s = schedule_at(recipe, it);
    if (s.ball_spread != spread) {
      spread = s.ball_spread;  // the same draws, scaled: only the ball moves
      data = render_scene_set(recipe.dataset_size, recipe.seed, kTrainStream, o.threads, spread);
      fmt::print("it {}: training images re-rendered with ball spread {:.4f}\n", it, spread);
    }
    const torch::Tensor x = gather_images(data.images, sampler.indices(it));
    if (it == recipe.revive_at) {
      std::array<int, 11> n{};
      const LatentMask revived =
          model->revive(x, recipe.recycle_threshold, recipe.recycle_outgoing_scale,
                        recipe.out_init_scale, 0.1, recipe.revive_fresh_decoder, n);
      optimizer.state().clear();
      std::string which;
      for (int l = 0; l < kLatents; ++l)
        if (revived[static_cast<size_t>(l)]) {
          which += fmt::format(" z{}", l);
          held[static_cast<size_t>(l)] = false;
        }
      fmt::print("it {}: revived: encoder units recycled conv0..3 {} {} {} {} fc1 {} fc2 {}; "
                 "decoder {}; fresh latents{}\n",
                 it, n[0], n[1], n[2], n[3], n[4], n[5],
                 recipe.revive_fresh_decoder
                     ? std::string("re-initialised")
                     : fmt::format("units recycled fc1 {} fc2 {} deconv0..2 {} {} {}", n[6], n[7],
                                   n[8], n[9], n[10]),
                 which);
    }
    const int trained = trained_latents(recipe, it);
    // Reconstruction costs only when a stage is about to hold latents (a few decoder passes).
    const bool pruning = trained < kLatents - std::count(held.begin(), held.end(), true);
    const auto importance = pruning && recipe.prune_by == "recon"
                                ? model->reconstruction_cost_of_each_latent(x)
                                : kl_ema;
    if (update_held_latents(model, held, trained, importance, recipe.out_init_scale)) {
      for (auto* layer : {&model->enc->fc_out, &model->dec->fc1})
        for (const auto& p : (*layer)->parameters())
          optimizer.state().erase(c10::guts::to_string(p.unsafeGetTensorImpl()));
      std::string which;
      for (int l = 0; l < kLatents; ++l)
        if (!held[static_cast<size_t>(l)]) which += fmt::format(" z{}", l);
      fmt::print("it {}: {} latents train:{}\n", it, trained, which);
    }
    const bool holding = trained < kLatents;
    for (auto& group : optimizer.param_groups())
      static_cast<torch::optim::AdamOptions&>(group.options()).lr(s.lr);

    auto [mu, logvar] = model->enc->forward(x);
    const auto z = mu + torch::randn_like(mu) * (0.5 * logvar).exp();
    const auto logits = model->dec->forward(z);
    const auto recon = torch::binary_cross_entropy_with_logits(logits, x, {}, {}, at::Reduction::Sum) /
                       static_cast<double>(recipe.batch);
    const auto kl_latent = kl_per_latent(mu, logvar);
    const auto kl = kl_latent.sum();
    const auto loss = recon + s.beta * (kl - s.capacity).abs();
    optimizer.zero_grad();
    loss.backward();
    if (holding) model->mask_held_gradients(held);
    if (encoder_frozen_at(recipe, it)) {
      model->drop_encoder_feature_gradients(recipe.freeze_convs_only);
      if (recipe.freeze_decoder_too) model->drop_decoder_feature_gradients();
    }
    optimizer.step();
    if (recipe.recycle_every > 0 && (it + 1) % recipe.recycle_every == 0) {
      const auto n = model->recycle_dormant_encoder_units(x, recipe.recycle_threshold,
                                                         recipe.recycle_outgoing_scale);
      fmt::print("it {}: recycled dormant encoder units conv0..3 {} {} {} {} fc1 {} fc2 {}\n",
                 it + 1, n[0], n[1], n[2], n[3], n[4], n[5]);
      if (recipe.recycle_decoder_too) {
        torch::Tensor z;
        {
          torch::NoGradGuard no_grad;
          z = model->enc->forward(x).first;
        }
        const auto d = model->recycle_dormant_decoder_units(z, recipe.recycle_threshold,
                                                            recipe.recycle_outgoing_scale);
        fmt::print("it {}: recycled dormant decoder units fc1 {} fc2 {} deconv0..2 {} {} {}\n",
                   it + 1, d[0], d[1], d[2], d[3], d[4]);
      }
    }
    if (frozen_rows.defined()) {
      // After the step and any recycling, so neither the gradient, Adam's momentum nor a
      // recycled unit's fresh outgoing weights move them.
      torch::NoGradGuard no_grad;
      model->enc->fc_out->weight.index_copy_(0, frozen_rows, frozen_weight);
      model->enc->fc_out->bias.index_copy_(0, frozen_rows, frozen_bias);
    }

    w_loss += loss.item<double>();
    w_recon += recon.item<double>();
    w_kl += kl.item<double>();
    w_kl_latent += kl_latent.detach().to(torch::kFloat64);
    {
      const auto k = kl_latent.detach().to(torch::kFloat64).contiguous();
      for (size_t l = 0; l < kl_ema.size(); ++l)
        kl_ema[l] += 0.02 * (k.data_ptr<double>()[l] - kl_ema[l]);  // ~50-iteration memory
    }
    ++w_n;
    const int64_t done = it + 1;
    if (done % o.log_every == 0 || done == recipe.iterations) {
      const auto now = Clock::now();
      const double rate = static_cast<double>(w_n) /
                          std::chrono::duration<double>(now - window_start).count();
      const double overall = static_cast<double>(done - start) /
                             std::chrono::duration<double>(now - run_start).count();
      const auto klw = (w_kl_latent / static_cast<double>(w_n)).contiguous();
      const std::vector<double> kls(klw.data_ptr<double>(), klw.data_ptr<double>() + kLatents);
      const double n = static_cast<double>(w_n);
      fmt::print(
          "it {}/{} | {:.2f} it/s | loss {:.2f} recon {:.2f} kl {:.2f} | C {:.2f} beta {:.0f} lr "
          "{:.1e} | ETA {} | kl/z {}\n",
          done, recipe.iterations, rate, w_loss / n, w_recon / n, w_kl / n, s.capacity, s.beta,
          s.lr, format_duration(static_cast<double>(recipe.iterations - done) / overall),
          kl_list(kls));
      std::fflush(stdout);
      csv << fmt::format("{},{:.4f},{:.4f},{:.4f},{},{:.4f},{:.3e},{:.3f}", done, w_loss / n,
                         w_recon / n, w_kl / n, s.beta, s.capacity, s.lr, rate);
      for (double v : kls) csv << fmt::format(",{:.5f}", v);
      csv << "\n" << std::flush;
      w_loss = w_recon = w_kl = 0;
      w_kl_latent.zero_();
      w_n = 0;
      window_start = now;
    }
    if (o.eval_every > 0 && done % o.eval_every == 0) {
      model->eval();
      double recon = 0.0;
      const FactorReport r = evaluate_factors(model, recipe.model, eval_set, {}, &recon);
      model->train();
      fmt::print("eval it {} | held-out recon {:.2f} | kl/z {}\n{}", done, recon,
                 kl_list(r.kl_per_latent), summary_text(r));
      nlohmann::json j = to_json(r);
      j["iteration"] = done;
      j["recon"] = recon;
      std::ofstream(fs::path(o.out_dir) / "eval.jsonl", std::ios::app) << j.dump() << "\n";
    }
    if (done % o.checkpoint_every == 0 || done == recipe.iterations || g_stop) {
      save_checkpoint(ckpt, model, optimizer, recipe, done);
      if (g_stop) {
        fmt::print("stopped at iteration {}; checkpoint {}; continue with --resume\n", done, ckpt);
        return 130;
      }
    }
  }
  fmt::print("training done in {} ({} iterations this run)\n",
             format_duration(std::chrono::duration<double>(Clock::now() - run_start).count()),
             recipe.iterations - start);
  if (o.report_images > 0) {
    const FactorReport r = write_outputs(model, recipe, o.out_dir, o.report_images, o.threads);
    fmt::print("factor report ({} held-out images) -> {}\n{}", o.report_images,
               (fs::path(o.out_dir) / "factor_report.json").string(), summary_text(r));
  }
  return 0;
}

int run_report(const std::string& dir, int64_t images, int threads) {
  if (images < 2) throw std::runtime_error("--images must be ≥ 2");
  torch::set_num_threads(threads);
  Vae model;
  const CheckpointInfo info = load_checkpoint(checkpoint_path(dir), model, nullptr);
  const FactorReport r = write_outputs(model, info.recipe, dir, images, threads);
  fmt::print("{} at iteration {}, {} held-out images -> {}\n{}", info.recipe.model, info.iteration,
             images, (fs::path(dir) / "factor_report.json").string(), summary_text(r));
  return r.pass ? 0 : 2;
}

int run_unmix(const std::string& from, const std::string& out_dir, int64_t images, int threads) {
  if (images < 100) throw std::runtime_error("--images must be ≥ 100");
  torch::set_num_threads(threads);
  Vae model;
  const CheckpointInfo info = load_checkpoint(from, model, nullptr);
  model->eval();
  // The recipe's own training images (same seed and stream, or its --scenes file): unmixing
  // is a training step.
  const SceneSet train_set = info.recipe.scenes_file.empty()
                                 ? render_scene_set(images, info.recipe.seed, kTrainStream, threads)
                                 : load_scene_set_csv(info.recipe.scenes_file, threads);
  const SceneSet check_set = render_scene_set(2000, info.recipe.seed, kEvalStream, threads);
  auto check = [&](const char* when) {
    double recon = 0.0;
    const FactorReport r = evaluate_factors(model, info.recipe.model, check_set, {}, &recon);
    fmt::print("{}: held-out recon {:.2f}\n{}", when, recon, summary_text(r));
  };
  check("before");
  const UnmixResult u = unmix_active_latents(model, train_set.images, info.recipe.seed);
  fmt::print("FastICA on {} latents ({} images): {} after {} iterations; excess kurtosis",
             u.active.size(), train_set.images.size(0), u.ica.converged ? "converged" : "NOT converged",
             u.ica.iterations);
  for (double k : u.excess_kurtosis) fmt::print(" {:.2f}", k);
  fmt::print(" (uniform sources: -1.20, Gaussian: 0)\n");
  check("after");
  fs::create_directories(out_dir);
  torch::optim::Adam optimizer(model->parameters(), torch::optim::AdamOptions(info.recipe.lr));
  const std::string ckpt = checkpoint_path(out_dir);
  save_checkpoint(ckpt, model, optimizer, info.recipe, info.iteration);
  fmt::print("wrote {} (continue with train --init-from {})\n", ckpt, ckpt);
  return 0;
}

}  // namespace curio::train
