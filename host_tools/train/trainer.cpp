// The training loop of `curio-train train`: setup, then per iteration schedule → training
// images (ball spread) → latent stage → Adam step → log / held-out check / checkpoint, with
// the recorded trials' hooks (trial_hooks.hpp) at their points.
#include "host_tools/train/trainer.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>
#include <torch/torch.h>

#include "firmware/explore/prng.hpp"
#include "host_tools/common/atomic_file.hpp"
#include "host_tools/train/blas_info.hpp"
#include "host_tools/vae/checkpoint.hpp"
#include "host_tools/vae/evaluate.hpp"
#include "host_tools/train/figures.hpp"
#include "host_tools/vae/latent_unmixing.hpp"
#include "host_tools/vae/scene_set.hpp"
#include "host_tools/train/training_hook.hpp"
#include "host_tools/train/trial_hooks.hpp"
#include "host_tools/vae/vae_model.hpp"

namespace curio::train {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::atomic<int> g_stop{0};  // the signal that stops the training (0: none)
static_assert(std::atomic<int>::is_always_lock_free, "set from a signal handler");
extern "C" void on_stop_signal(int sig) { g_stop = sig; }

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

// Result files are replaced atomically (temp + fsync + rename): a kill leaves the old file or
// the new one. The training CSV and eval.jsonl grow by appended lines (a resume cuts the CSV
// back to its checkpoint).
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
  host::write_file_atomically_or_throw(path, kept);
}

void check_recipe(const Recipe& r) {
  if (const std::string problem = recipe_problem(r); !problem.empty())
    throw std::runtime_error(problem);
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
  host::write_file_atomically_or_throw((fs::path(dir) / "factor_report.json").string(),
                                      to_json(report).dump(2) + "\n");

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
// or what a pruning hook measures). Returns whether anything changed.
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

using Hooks = std::vector<std::unique_ptr<TrainingHook>>;

// The run's files in its output directory.
struct RunFiles {
  std::string checkpoint, csv;
  fs::path dir;
};

RunFiles prepare_out_dir(const TrainOptions& o) {
  fs::create_directories(o.out_dir);
  RunFiles f{checkpoint_path(o.out_dir), (fs::path(o.out_dir) / "training.csv").string(), o.out_dir};
  if (!o.resume && fs::exists(f.checkpoint))
    throw std::runtime_error(f.checkpoint +
                             " exists: pass --resume to continue it, or choose another --out");
  return f;
}

// The model a run starts from: the seeded initialisation, then --init-from's weights unless
// the run resumes (its checkpoint overwrites them).
Vae initial_model(const Recipe& recipe, bool resuming) {
  torch::manual_seed(recipe.seed);
  Vae model;
  initialise_weights(model, recipe);
  if (!recipe.init_from.empty() && !resuming) {
    const CheckpointInfo from = load_checkpoint(recipe.init_from, model, nullptr);
    fmt::print("initialised from {} ({} at iteration {})\n", recipe.init_from, from.recipe.model,
               from.iteration);
  }
  return model;
}

// The latents stage 0 holds in a fresh model (an --init-from model keeps its own until the
// data exist: apply_initial_stage).
LatentMask initial_held_latents(Vae& model, const Recipe& recipe) {
  if (!recipe.init_from.empty()) return model->held_latents();
  LatentMask held{};
  for (int l = trained_latents(recipe, 0); l < kLatents; ++l) held[static_cast<size_t>(l)] = true;
  model->hold_latents(held);
  return held;
}

// Continues the checkpoint in the output directory (its recipe governs; only the length may
// change) or starts a fresh CSV. Returns the first iteration to train.
int64_t resume_or_start(const TrainOptions& o, const RunFiles& f, Recipe& recipe, Vae& model,
                        torch::optim::Adam& optimizer, LatentMask& held) {
  if (o.resume && fs::exists(f.checkpoint)) {
    const CheckpointInfo info = load_checkpoint(f.checkpoint, model, &optimizer);
    const int64_t wanted = recipe.iterations;
    recipe = info.recipe;
    recipe.iterations = wanted;
    held = model->held_latents();
    truncate_csv(f.csv, info.iteration);
    fmt::print("resumed {} at iteration {} (recipe from the checkpoint, iterations {}{})\n",
               f.checkpoint, info.iteration, recipe.iterations,
               info.verified ? "; its CRC-32 checked" : "; no .crc beside it: not verified");
    return info.iteration;
  }
  host::write_file_atomically_or_throw(
      f.csv, kCsvHeader + [] {
        std::string s;
        for (int l = 0; l < kLatents; ++l) s += fmt::format(",kl_z{}", l);
        return s;
      }() + "\n");
  fs::remove(f.dir / "eval.jsonl");
  return 0;
}

// The training images and the ball spread they were rendered with.
struct TrainingData {
  SceneSet set;
  double spread;
};

// The one place a run's training images come from.
TrainingData render_training_data(const Recipe& recipe, double spread, int threads) {
  return {render_scene_set(recipe.dataset_size, recipe.seed, kTrainStream, threads, spread), spread};
}

// --scenes: the exploration's own images, all of them (dataset_size becomes their count);
// an undefined set otherwise.
SceneSet scenes_of_file(Recipe& recipe, int threads) {
  if (recipe.scenes_file.empty()) return {};
  SceneSet scenes = load_scene_set_csv(recipe.scenes_file, threads);
  recipe.dataset_size = scenes.images.size(0);
  check_recipe(recipe);
  return scenes;
}

// The training images of the run's first iteration, after a note when the ball does not span
// SPEC §3's range.
TrainingData first_training_data(const Recipe& recipe, int64_t start, int threads) {
  const double spread = schedule_at(recipe, start).ball_spread;
  if (spread < 1.0 || recipe.ball_spread_iters > 0)
    fmt::print("curriculum: training images draw the ball in [-{0}, {0}]^2, not SPEC §3's "
               "[-1, 1]^2{1}\n", spread,
               recipe.ball_spread_iters > 0
                   ? fmt::format(" (moving to {} by iteration {})", recipe.ball_spread_to,
                                 recipe.ball_spread_iters)
                   : std::string{});
  return render_training_data(recipe, spread, threads);
}

// Re-renders the training images when the schedule has moved the ball spread by a step (the
// same draws, scaled: only the ball moves).
void follow_ball_spread(TrainingData& data, const Recipe& recipe, const ScheduleAt& s, int64_t it,
                        int threads) {
  if (s.ball_spread == data.spread) return;
  data = render_training_data(recipe, s.ball_spread, threads);
  fmt::print("it {}: training images re-rendered with ball spread {:.4f}\n", it, data.spread);
}

// Per-latent KL of an --init-from model on the first training images.
std::array<double, kLatents> initial_kl(Vae& model, const Recipe& recipe, const SceneSet& data) {
  torch::NoGradGuard no_grad;
  const auto idx = torch::arange(std::min<int64_t>(512, recipe.dataset_size));
  auto [mu, logvar] = model->enc->forward(gather_images(data.images, idx));
  const auto k = kl_per_latent(mu, logvar).to(torch::kFloat64).contiguous();
  std::array<double, kLatents> kl{};
  for (size_t l = 0; l < kl.size(); ++l) kl[l] = k.data_ptr<double>()[l];
  return kl;
}

// An --init-from model keeps its strongest latents when stage 0 trains fewer than it has.
void apply_initial_stage(TrainingState& st) {
  torch::NoGradGuard no_grad;
  const int trained = trained_latents(st.recipe, 0);
  if (update_held_latents(st.model, st.held, trained, st.kl_ema, st.recipe.out_init_scale))
    fmt::print("it 0: {} latents train (lowest-KL latents of the initial model held)\n", trained);
}

// Applies the iteration's latent stage (fresh latents get fresh Adam state); returns how many
// latents train.
int apply_latent_stage(TrainingState& st, const Hooks& hooks, int64_t it, const torch::Tensor& x) {
  const int trained = trained_latents(st.recipe, it);
  const bool pruning = trained < kLatents - std::count(st.held.begin(), st.held.end(), true);
  std::array<double, kLatents> importance = st.kl_ema;
  if (pruning)
    for (const auto& h : hooks)
      if (h->pruning_importance(st, x, importance)) break;
  if (!update_held_latents(st.model, st.held, trained, importance, st.recipe.out_init_scale))
    return trained;
  forget_adam_state(st.optimizer, *st.model->enc->fc_out);
  forget_adam_state(st.optimizer, *st.model->dec->fc1);
  std::string which;
  for (int l = 0; l < kLatents; ++l)
    if (!st.held[static_cast<size_t>(l)]) which += fmt::format(" z{}", l);
  fmt::print("it {}: {} latents train:{}\n", it, trained, which);
  return trained;
}

struct StepLosses {
  torch::Tensor loss, recon, kl, kl_latent;
};

// One Adam step on the objective recon + β·|KL − C| (SPEC §3) at the schedule's lr.
StepLosses train_step(TrainingState& st, const Hooks& hooks, const ScheduleAt& s, int trained,
                      int64_t it, const torch::Tensor& x) {
  for (auto& group : st.optimizer.param_groups())
    static_cast<torch::optim::AdamOptions&>(group.options()).lr(s.lr);
  auto [mu, logvar] = st.model->enc->forward(x);
  const auto z = mu + torch::randn_like(mu) * (0.5 * logvar).exp();
  const auto logits = st.model->dec->forward(z);
  StepLosses l;
  l.recon = torch::binary_cross_entropy_with_logits(logits, x, {}, {}, at::Reduction::Sum) /
            static_cast<double>(st.recipe.batch);
  l.kl_latent = kl_per_latent(mu, logvar);
  l.kl = l.kl_latent.sum();
  l.loss = l.recon + s.beta * (l.kl - s.capacity).abs();
  st.optimizer.zero_grad();
  l.loss.backward();
  if (trained < kLatents) st.model->mask_held_gradients(st.held);
  for (const auto& h : hooks) h->after_backward(st, it);
  st.optimizer.step();
  return l;
}

void update_kl_ema(std::array<double, kLatents>& kl_ema, const torch::Tensor& kl_latent) {
  const auto k = kl_latent.detach().to(torch::kFloat64).contiguous();
  for (size_t l = 0; l < kl_ema.size(); ++l)
    kl_ema[l] += 0.02 * (k.data_ptr<double>()[l] - kl_ema[l]);  // ~50-iteration memory
}

bool all_finite(Vae& model) {
  torch::NoGradGuard no_grad;
  for (const auto& p : model->parameters())
    if (!torch::isfinite(p).all().item<bool>()) return false;
  return true;
}

// The losses since the last progress line, written as that line and a CSV row.
class LossWindow {
 public:
  explicit LossWindow(Clock::time_point start) : start_(start) {}

  // `loss`: l.loss as a number (the loop reads it once, to check it is finite).
  void add(const StepLosses& l, double loss) {
    loss_ += loss;
    recon_ += l.recon.item<double>();
    kl_ += l.kl.item<double>();
    kl_latent_ += l.kl_latent.detach().to(torch::kFloat64);
    ++n_;
  }

  // The ETA counts from the run's (re)start: iteration `start` at `run_start`.
  void report(int64_t done, int64_t iterations, int64_t start, Clock::time_point run_start,
              const ScheduleAt& s, std::ofstream& csv) {
    const auto now = Clock::now();
    const double rate =
        static_cast<double>(n_) / std::chrono::duration<double>(now - start_).count();
    const double overall = static_cast<double>(done - start) /
                           std::chrono::duration<double>(now - run_start).count();
    const auto klw = (kl_latent_ / static_cast<double>(n_)).contiguous();
    const std::vector<double> kls(klw.data_ptr<double>(), klw.data_ptr<double>() + kLatents);
    const double n = static_cast<double>(n_);
    fmt::print(
        "it {}/{} | {:.2f} it/s | loss {:.2f} recon {:.2f} kl {:.2f} | C {:.2f} beta {:.0f} lr "
        "{:.1e} | ETA {} | kl/z {}\n",
        done, iterations, rate, loss_ / n, recon_ / n, kl_ / n, s.capacity, s.beta, s.lr,
        format_duration(static_cast<double>(iterations - done) / overall), kl_list(kls));
    std::fflush(stdout);
    csv << fmt::format("{},{:.4f},{:.4f},{:.4f},{},{:.4f},{:.3e},{:.3f}", done, loss_ / n,
                       recon_ / n, kl_ / n, s.beta, s.capacity, s.lr, rate);
    for (double v : kls) csv << fmt::format(",{:.5f}", v);
    csv << "\n" << std::flush;
    loss_ = recon_ = kl_ = 0;
    kl_latent_.zero_();
    n_ = 0;
    start_ = now;
  }

 private:
  Clock::time_point start_;
  double loss_ = 0, recon_ = 0, kl_ = 0;
  torch::Tensor kl_latent_ = torch::zeros({kLatents}, torch::kFloat64);
  int64_t n_ = 0;
};

// The held-out factor check: a progress line and a row of eval.jsonl.
void evaluate_held_out(Vae& model, const Recipe& recipe, const SceneSet& eval_set, int64_t done,
                       const RunFiles& f) {
  model->eval();
  double recon = 0.0;
  const FactorReport r = evaluate_factors(model, recipe.model, eval_set, {}, &recon);
  model->train();
  fmt::print("eval it {} | held-out recon {:.2f} | kl/z {}\n{}", done, recon,
             kl_list(r.kl_per_latent), summary_text(r));
  nlohmann::json j = to_json(r);
  j["iteration"] = done;
  j["recon"] = recon;
  std::ofstream(f.dir / "eval.jsonl", std::ios::app) << j.dump() << "\n";
}

}  // namespace

std::string recipe_problem(const Recipe& r) {
  if (r.model != "beta-vae" && r.model != "vae")
    return "--kind must be beta-vae or vae, not '" + r.model + "'";
  if (r.iterations < 1 || r.batch < 1) return "--iterations and --batch must be >= 1";
  if (r.dataset_size < r.batch)
    return fmt::format("--dataset-size {} is smaller than --batch {}", r.dataset_size, r.batch);
  if (!(r.lr > 0.0)) return "--lr must be > 0";
  if (!r.scenes_file.empty() && (r.ball_spread < 1.0 || r.ball_spread_iters > 0))
    return "--scenes trains on the file's scenes as they are: no --ball-spread";
  return "";
}

int run_training(const TrainOptions& o) {
  Recipe recipe = o.recipe;
  check_recipe(recipe);
  const RunFiles files = prepare_out_dir(o);
  torch::set_num_threads(o.threads);
  print_blas(torch::get_num_threads());

  Vae model = initial_model(recipe, o.resume && fs::exists(files.checkpoint));
  LatentMask held = initial_held_latents(model, recipe);
  torch::optim::Adam optimizer(model->parameters(), torch::optim::AdamOptions(recipe.lr));
  const int64_t start = resume_or_start(o, files, recipe, model, optimizer, held);
  SceneSet scenes = scenes_of_file(recipe, o.threads);
  host::write_file_atomically_or_throw((files.dir / "recipe.json").string(),
                                      to_json(recipe).dump(2) + "\n");
  fmt::print("recipe: {}\n", to_json(recipe).dump());

  const auto t0 = Clock::now();
  TrainingData data = scenes.images.defined() ? TrainingData{std::move(scenes), 1.0}
                                              : first_training_data(recipe, start, o.threads);
  const SceneSet eval_set = o.eval_every > 0
                                ? render_scene_set(o.eval_images, recipe.seed, kEvalStream, o.threads)
                                : SceneSet{};
  fmt::print("rendered {} training + {} held-out images in {:.1f} s\n", recipe.dataset_size,
             o.eval_every > 0 ? o.eval_images : 0,
             std::chrono::duration<double>(Clock::now() - t0).count());

  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
  BatchSampler sampler(recipe.dataset_size, recipe.batch, recipe.seed);
  std::ofstream csv(files.csv, std::ios::app);
  const auto run_start = Clock::now();
  LossWindow window(run_start);
  std::array<double, kLatents> kl_ema{};
  TrainingState st{recipe, model, optimizer, held, kl_ema};
  const Hooks hooks = make_trial_hooks(recipe.trial);
  const bool fresh_init_from = !recipe.init_from.empty() && start == 0;
  if (fresh_init_from) kl_ema = initial_kl(model, recipe, data.set);
  for (const auto& h : hooks) h->on_start(st, start);
  if (fresh_init_from) apply_initial_stage(st);

  model->train();
  int64_t last_saved = start;  // the iteration the checkpoint on disk holds (0: none)
  for (int64_t it = start; it < recipe.iterations; ++it) {
    for (const auto& h : hooks) h->on_iteration_start(st, it);
    const ScheduleAt s = schedule_at(recipe, it);
    follow_ball_spread(data, recipe, s, it, o.threads);
    const torch::Tensor x = gather_images(data.set.images, sampler.indices(it));
    for (const auto& h : hooks) h->before_latent_stage(st, it, x);
    const int trained = apply_latent_stage(st, hooks, it, x);
    const StepLosses step = train_step(st, hooks, s, trained, it, x);
    for (const auto& h : hooks) h->after_step(st, it, x);
    const int64_t done = it + 1;
    const bool saving =
        done % o.checkpoint_every == 0 || done == recipe.iterations || g_stop != 0;
    // Nothing after a NaN is worth keeping: stop before the checkpoint is overwritten (a step
    // with a finite loss can still leave non-finite weights: checked before every save).
    const double loss = step.loss.item<double>();
    if (!std::isfinite(loss) || (saving && !all_finite(model))) {
      fmt::print(stderr,
                 "curio-train: the {} not finite ({}) at iteration {}; stopped without "
                 "saving: {}\n",
                 std::isfinite(loss) ? "weights are" : "loss is", loss, done,
                 last_saved > 0 ? fmt::format("{} keeps iteration {} (lower --lr, or check the "
                                              "data; --resume continues from it)",
                                              files.checkpoint, last_saved)
                                : std::string("no checkpoint was written yet"));
      return 1;
    }
    window.add(step, loss);
    update_kl_ema(kl_ema, step.kl_latent);

    if (done % o.log_every == 0 || done == recipe.iterations)
      window.report(done, recipe.iterations, start, run_start, s, csv);
    if (o.eval_every > 0 && done % o.eval_every == 0)
      evaluate_held_out(model, recipe, eval_set, done, files);
    if (saving) {
      save_checkpoint(files.checkpoint, model, optimizer, recipe, done);
      last_saved = done;
      if (g_stop != 0) {
        fmt::print("stopped at iteration {}; checkpoint {}; continue with --resume\n", done,
                   files.checkpoint);
        return 128 + g_stop;  // 130 after SIGINT, 143 after SIGTERM
      }
    }
  }
  fmt::print("training done in {} ({} iterations this run)\n",
             format_duration(std::chrono::duration<double>(Clock::now() - run_start).count()),
             recipe.iterations - start);
  if (o.report_images > 0) {
    const FactorReport r = write_outputs(model, recipe, o.out_dir, o.report_images, o.threads);
    fmt::print("factor report ({} held-out images) -> {}\n{}", o.report_images,
               (files.dir / "factor_report.json").string(), summary_text(r));
  }
  return 0;
}

int run_report(const std::string& checkpoint, int64_t images, int threads) {
  if (images < 2) throw std::runtime_error("--images must be >= 2");
  torch::set_num_threads(threads);
  Vae model;
  const CheckpointInfo info = load_checkpoint(checkpoint, model, nullptr);
  const fs::path parent = fs::path(checkpoint).parent_path();
  const std::string dir = parent.empty() ? std::string(".") : parent.string();
  const FactorReport r = write_outputs(model, info.recipe, dir, images, threads);
  fmt::print("{} at iteration {}, {} held-out images -> {}\n{}", info.recipe.model, info.iteration,
             images, (fs::path(dir) / "factor_report.json").string(), summary_text(r));
  return r.pass ? 0 : 1;
}

int run_unmix(const std::string& from, const std::string& out_dir, int64_t images, int threads) {
  if (images < 100) throw std::runtime_error("--images must be >= 100");
  torch::set_num_threads(threads);
  Vae model;
  const CheckpointInfo info = load_checkpoint(from, model, nullptr);
  model->eval();
  // The recipe's own training images (same seed and stream): unmixing is a training step.
  // (or its --scenes file)
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
