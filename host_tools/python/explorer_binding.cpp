// curio.Explorer: the firmware Explorer (firmware/explore/explorer.hpp) with curio-lab's
// algorithms (the same RunSpec, hence the same archive for the same seed) or with modules the
// user declares over any outcome vector; ask/tell (propose/observe) or the C++ loop run(world);
// what the run recorded as numpy arrays, most of them views of the C++ buffers.
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "firmware/app/episode_outcome.hpp"
#include "firmware/explore/fnv1a.hpp"
#include "firmware/explore/module_layouts.hpp"
#include "firmware/nn/encoder.hpp"
#include "host_tools/experiment/campaign_config.hpp"
#include "host_tools/experiment/controllability.hpp"
#include "host_tools/experiment/explore_strategies.hpp"
#include "host_tools/experiment/run_explorer.hpp"
#include "host_tools/python/bindings.hpp"
#include "sim/camera.hpp"

namespace curio::python {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr int kSceneValues = 4;  // ball x, ball y, distractor x, distractor y

std::string known_algorithm_names() {
  std::string known = "RPE, RGE, MGE (with modules=...)";
  for (const auto& s : lab::known_algorithms()) known += ", " + s.name;
  return known;
}

// The verdicts of classify_modules as a dict of numpy arrays (one entry per module).
py::dict verdict_dict(const std::vector<lab::ModuleVerdict>& v) {
  const auto n = static_cast<py::ssize_t>(v.size());
  py::array_t<int32_t> exploits(n);
  py::array_t<double> mean_progress(n), t(n), mean_interest(n), relative(n);
  py::array_t<bool> controllable(n);
  for (py::ssize_t k = 0; k < n; ++k) {
    const auto& m = v[static_cast<size_t>(k)];
    exploits.mutable_at(k) = m.exploits;
    mean_progress.mutable_at(k) = m.mean_progress;
    t.mutable_at(k) = m.t;
    mean_interest.mutable_at(k) = m.mean_interest;
    relative.mutable_at(k) = m.relative_interest;
    controllable.mutable_at(k) = m.controllable;
  }
  py::dict d;
  d["controllable"] = controllable;
  d["t"] = t;
  d["relative_interest"] = relative;
  d["mean_progress"] = mean_progress;
  d["mean_interest"] = mean_interest;
  d["exploits"] = exploits;
  return d;
}

class PyExplorer {
 public:
  PyExplorer(const std::string& algorithm, uint64_t seed, int episodes, int bootstrap,
             double sigma, double competence_clip, double window, double epsilon,
             const std::string& tie_rule, const std::string& competence_measure,
             const std::string& explore, const py::object& modules, int outcome_dim,
             const std::string& goals, double goal_bound, int interest_every);

  py::array_t<float> propose();
  void observe(const py::object& outcome);
  int run(const py::object& world, int episodes);
  uint32_t checksum() const {
    Fnv1a f;
    f.add_archive(ex().archive());
    return f.h;
  }

  const Explorer& ex() const { return *x_.explorer; }
  Explorer& ex() { return *x_.explorer; }
  int size() const { return ex().archive().size(); }
  const std::string& algorithm() const { return algorithm_; }
  const std::vector<std::string>& module_names() const { return module_names_; }
  bool learned() const { return x_.encoder != nullptr; }
  int goal_width() const { return goal_width_; }
  int interest_samples() const { return static_cast<int>(interest_episodes_.size()); }

  // Buffers the numpy views read (sized for the whole run at construction, never moved).
  std::vector<uint8_t> kinds_;
  std::vector<int8_t> modules_;
  std::vector<float> goals_;     // total × goal_width_
  std::vector<float> progress_;  // NaN but for exploits
  std::vector<float> scenes_;    // total × 4, NaN but for run() on a curio.World
  std::vector<uint8_t> grasped_;
  std::vector<float> interest_;  // samples × n_modules
  std::vector<int32_t> interest_episodes_;
  std::vector<lab::ProgressSample> exploits_;
  int interest_every_ = 50;

  py::dict verdicts(double min_t, double min_relative_interest) const {
    std::vector<std::vector<float>> interest;
    const int k = ex().n_modules();
    for (int s = 0; s < interest_samples(); ++s)
      interest.emplace_back(interest_.begin() + s * k, interest_.begin() + (s + 1) * k);
    std::vector<int> episodes(interest_episodes_.begin(), interest_episodes_.end());
    return verdict_dict(lab::classify_modules(exploits_, interest, episodes,
                                              ex().config().n_bootstrap, ex().total_episodes(),
                                              {min_t, min_relative_interest}));
  }

  void check_idle() const {
    if (busy_) throw py::value_error("explorer: in use by run() in another thread");
  }

 private:
  void check_can_propose() const {
    if (ex().done())
      throw py::value_error("propose(): the run is done (" + std::to_string(ex().total_episodes()) +
                            " episodes)");
  }
  // Store outcome[] for the pending episode and record what the run keeps of it.
  void observe_values(const float* outcome, const sim::SceneState* scene);
  void record_interest(int n);
  std::vector<float> outcome_from(const py::object& outcome);

  lab::RunExplorer x_;
  std::string algorithm_;
  std::vector<std::string> module_names_;
  int goal_width_ = 1;
  bool busy_ = false;
};

PyExplorer::PyExplorer(const std::string& algorithm, uint64_t seed, int episodes, int bootstrap,
                       double sigma, double competence_clip, double window, double epsilon,
                       const std::string& tie_rule, const std::string& competence_measure,
                       const std::string& explore, const py::object& modules, int outcome_dim,
                       const std::string& goals, double goal_bound, int interest_every)
    : interest_every_(interest_every), algorithm_(algorithm) {
  if (episodes < 0) value_error("episodes", "expected a number >= 0");
  if (bootstrap < -1) value_error("bootstrap", "expected a number >= 0 (or None: the default)");
  if (!(sigma >= 0.0) || !std::isfinite(sigma)) value_error("sigma", "expected a finite number >= 0");
  if (!(competence_clip > 0.0 || competence_clip == -1.0) || !std::isfinite(competence_clip))
    value_error("competence_clip", "expected a number > 0 (or None: the default)");
  if (!(window >= 1.0) || !std::isfinite(window)) value_error("window", "expected a number >= 1");
  if (!(epsilon >= 0.0 && epsilon <= 1.0)) value_error("epsilon", "expected a number in [0, 1]");
  if (interest_every < 1) value_error("interest_every", "expected a number >= 1");
  const auto tie = lab::parse_tie_rule(tie_rule);
  if (!tie) value_error("tie_rule", "expected 'latest' or 'earliest', got '" + tie_rule + "'");
  const auto measure = lab::parse_competence_measure(competence_measure);
  if (!measure)
    value_error("competence_measure", "expected 'clip' or 'scale', got '" + competence_measure + "'");
  const auto strategy = lab::find_explore_strategy(explore);
  if (!strategy)
    value_error("explore", "unknown strategy '" + explore + "' (known: " +
                               lab::explore_strategy_names() + ")");

  const bool bare = algorithm == "RPE" || algorithm == "RGE" || algorithm == "MGE";
  const bool custom = !modules.is_none() || (outcome_dim > 0) || algorithm == "RGE" || algorithm == "MGE";
  if (custom) {
    // Modules the user declares over an outcome vector of their own.
    if (!bare)
      value_error("modules", "declared modules need algorithm 'RGE', 'MGE' or 'RPE' (named "
                             "algorithms such as 'MGE-EFR' fix their own), got '" + algorithm + "'");
    ExplorerConfig& c = x_.config;
    c.algorithm = algorithm == "RPE" ? Algorithm::kRpe
                  : algorithm == "RGE" ? Algorithm::kRge
                                       : Algorithm::kMge;
    std::vector<std::vector<int>> dims;
    if (!modules.is_none()) {
      if (!py::isinstance<py::sequence>(modules) || py::isinstance<py::str>(modules))
        type_error("modules", "expected a list of lists of outcome indices, e.g. [[0, 1], [2, 3]]");
      for (const auto& m : modules.cast<py::sequence>()) {
        if (!py::isinstance<py::sequence>(m) || py::isinstance<py::str>(m))
          type_error("modules", "each module must be a list of outcome indices");
        std::vector<int> d;
        for (const auto& i : m.cast<py::sequence>()) {
          if (!PyIndex_Check(i.ptr()) || py::isinstance<py::bool_>(i))
            type_error("modules", "outcome indices must be int");
          const Py_ssize_t v = PyNumber_AsSsize_t(i.ptr(), nullptr);
          d.push_back(static_cast<int>(std::clamp<Py_ssize_t>(v, -1000, 1000)));  // range: below
        }
        dims.push_back(d);
      }
    }
    if (c.algorithm == Algorithm::kRpe && !dims.empty())
      value_error("modules", "RPE has no goal modules");
    if (c.algorithm != Algorithm::kRpe && dims.empty())
      value_error("modules", "RGE and MGE need modules, e.g. modules=[[0, 1], [2, 3]]");
    if (c.algorithm == Algorithm::kRge && dims.size() != 1)
      value_error("modules", "RGE has exactly one module (its goal space), got " +
                                 std::to_string(dims.size()));
    if (static_cast<int>(dims.size()) > kMaxModules)
      value_error("modules", "at most " + std::to_string(kMaxModules) + " modules");
    int max_dim = -1;
    for (const auto& d : dims)
      for (int i : d) max_dim = std::max(max_dim, i);
    if (outcome_dim == 0 && max_dim + 1 > kMaxOutcomeDim)
      value_error("modules", "index " + std::to_string(max_dim) + " needs an outcome of " +
                                 std::to_string(max_dim + 1) + " values; at most " +
                                 std::to_string(kMaxOutcomeDim));
    const int dim = outcome_dim > 0 ? outcome_dim : (max_dim + 1 > 0 ? max_dim + 1 : 0);
    if (dim < 1 || dim > kMaxOutcomeDim)
      value_error("outcome_dim", "expected 1.." + std::to_string(kMaxOutcomeDim) + " values per outcome");
    c.outcome_dim = dim;
    c.n_modules = static_cast<int>(dims.size());
    for (size_t k = 0; k < dims.size(); ++k) {
      const auto& d = dims[k];
      if (d.empty() || static_cast<int>(d.size()) > kMaxOutcomeDim)
        value_error("modules", "module " + std::to_string(k) + " needs 1.." +
                                   std::to_string(kMaxOutcomeDim) + " outcome indices");
      std::set<int> seen;
      std::string name;
      for (size_t j = 0; j < d.size(); ++j) {
        if (d[j] < 0 || d[j] >= dim)
          value_error("modules", "module " + std::to_string(k) + ": index " + std::to_string(d[j]) +
                                     " is outside the outcome (0.." + std::to_string(dim - 1) + ")");
        if (!seen.insert(d[j]).second)
          value_error("modules", "module " + std::to_string(k) + " repeats index " + std::to_string(d[j]));
        c.modules[k].dims[j] = static_cast<uint8_t>(d[j]);
        name += (j ? "+o" : "o") + std::to_string(d[j]);
      }
      c.modules[k].n_dims = static_cast<int>(d.size());
      module_names_.push_back(name);
    }
    if (goals == "box") c.goal_kind = GoalKind::kUniformBox;
    else if (goals == "normal") c.goal_kind = GoalKind::kClippedNormal;
    else value_error("goals", "expected 'box' (uniform in [-1, 1]^d) or 'normal' (clipped N(0, I)), got '" + goals + "'");
    if (!(goal_bound > 0.0) || !std::isfinite(goal_bound)) value_error("goal_bound", "expected a number > 0");
    c.goal_bound = static_cast<float>(goal_bound);
    c.sigma = static_cast<float>(sigma);
    c.competence_cap = static_cast<float>(competence_clip > 0 ? competence_clip : 2.0);
    c.competence_measure = *measure;
    c.window = static_cast<float>(window);
    c.epsilon = static_cast<float>(epsilon);
    c.n_bootstrap = bootstrap >= 0 ? bootstrap : 100;
    c.n_episodes = episodes;
    c.seed = seed;
    c.tie_rule = *tie;
    lab::apply_explore_strategy(*strategy, &c);
    if (c.algorithm != Algorithm::kRpe && episodes % 5 != 0)
      value_error("episodes", "expected a multiple of 5 (4 explore + 1 exploit per step)");
    if (c.n_bootstrap + c.n_episodes > kArchiveCapacity)
      value_error("episodes", "bootstrap + episodes must be at most the archive capacity " +
                                  std::to_string(kArchiveCapacity));
    if (const Status s = validate(c); s != Status::kOk)
      value_error("Explorer", std::string("the firmware explorer rejects this configuration: ") + to_string(s));
    x_.explorer = std::make_unique<Explorer>();
    if (const Status s = x_.explorer->init(c); s != Status::kOk)
      value_error("Explorer", std::string("init failed: ") + to_string(s));
  } else {
    // One of curio-lab's algorithms: the RunSpec curio-lab expands for this seed.
    if (!lab::find_algorithm(algorithm))
      value_error("algorithm", "unknown '" + algorithm + "' (known: " + known_algorithm_names() + ")");
    // curio-lab's own checks follow; these name the Python arguments.
    if (episodes <= 0) value_error("episodes", "expected a number > 0");
    if (episodes % 5 != 0)
      value_error("episodes", "expected a multiple of 5 (4 explore + 1 exploit per step)");
    const int n_bootstrap = bootstrap >= 0 ? bootstrap : lab::find_algorithm(algorithm)->default_bootstrap;
    if (static_cast<int64_t>(n_bootstrap) + episodes > kArchiveCapacity)
      value_error("episodes", "bootstrap (" + std::to_string(n_bootstrap) + ") + episodes must be at "
                              "most the archive capacity " + std::to_string(kArchiveCapacity));
    lab::CampaignConfig cc;
    cc.algorithms = {algorithm};
    cc.seeds = {seed};
    cc.sigmas = {sigma};
    cc.episodes = episodes;
    cc.bootstrap = bootstrap;
    cc.competence_clip = competence_clip;
    cc.window = window;
    cc.epsilon = epsilon;
    cc.tie_rule = *tie;
    cc.competence_measure = *measure;
    cc.explore = explore;
    const auto problems = lab::validate_campaign(cc);
    if (!problems.empty()) {
      std::string text;
      for (const auto& p : problems) text += (text.empty() ? "" : "; ") + p;
      // The campaign's messages name curio-lab's options; the Python names are the same words.
      value_error("Explorer", text);
    }
    lab::RunSpec spec = lab::expand_runs(cc).at(0);
    spec.interest_every = interest_every;
    std::string error;
    if (!lab::make_run_explorer(spec, &x_, &error)) value_error("Explorer", error);
    module_names_ = lab::module_names(spec.algorithm, x_.rep ? x_.rep->kl_order.data() : nullptr);
    algorithm_ = spec.algorithm.name;
  }

  const Explorer& e = ex();
  const auto total = static_cast<size_t>(e.total_episodes());
  for (int k = 0; k < e.n_modules(); ++k) goal_width_ = std::max(goal_width_, e.goal_module(k).n_dims);
  kinds_.assign(total, 0);
  modules_.assign(total, -1);
  goals_.assign(total * static_cast<size_t>(goal_width_), kNaN);
  progress_.assign(total, kNaN);
  scenes_.assign(total * kSceneValues, kNaN);
  grasped_.assign(total, 0);
  const size_t samples = total / static_cast<size_t>(interest_every) + 1;
  interest_.reserve(samples * static_cast<size_t>(e.n_modules()));
  interest_episodes_.reserve(samples);
  record_interest(0);
}

void PyExplorer::record_interest(int n) {
  const int k = ex().n_modules();
  if (k == 0 || n % interest_every_ != 0) return;
  for (int j = 0; j < k; ++j) interest_.push_back(ex().interest(j));
  interest_episodes_.push_back(n);
}

py::array_t<float> PyExplorer::propose() {
  check_idle();
  check_can_propose();
  py::array_t<float> theta(kThetaDim);
  if (const Status s = ex().propose(theta.mutable_data()); s != Status::kOk)
    throw py::value_error(std::string("propose(): ") + to_string(s));
  return theta;
}

std::vector<float> PyExplorer::outcome_from(const py::object& outcome) {
  if (learned() && py::isinstance<py::array>(outcome) && py::array(outcome).ndim() == 3) {
    bool single = false;
    const auto image = camera_images(outcome, "outcome", &single);
    std::vector<float> mu(nn::kLatents);
    if (!app::episode_outcome({}, x_.encoder.get(), image.data(), mu.data()))
      throw py::value_error("outcome: the encoder refused the image");
    return mu;
  }
  const int n = ex().config().outcome_dim;
  if (learned() && !(py::isinstance<py::array>(outcome) || py::isinstance<py::sequence>(outcome)))
    type_error("outcome", "expected a 64x64x3 uint8 camera image or " + std::to_string(n) + " latents");
  return finite_vector(outcome, n, "outcome");
}

void PyExplorer::observe(const py::object& outcome) {
  check_idle();
  if (!ex().pending()) throw py::value_error("observe(): no pending episode: call propose() first");
  const std::vector<float> v = outcome_from(outcome);
  observe_values(v.data(), nullptr);
}

void PyExplorer::observe_values(const float* outcome, const sim::SceneState* scene) {
  Explorer& e = ex();
  const int i = e.episode();
  const EpisodeKind kind = e.kind();
  const int module = e.module();
  const bool goal_step = module >= 0 && (kind == EpisodeKind::kExplore || kind == EpisodeKind::kExploit);
  if (const Status s = e.observe(outcome); s != Status::kOk)
    throw py::value_error(std::string("outcome: the explorer refused it: ") + to_string(s));
  const auto u = static_cast<size_t>(i);
  kinds_[u] = static_cast<uint8_t>(kind);
  modules_[u] = static_cast<int8_t>(goal_step ? module : -1);
  if (goal_step)
    for (int j = 0; j < e.goal_module(module).n_dims; ++j)
      goals_[u * static_cast<size_t>(goal_width_) + static_cast<size_t>(j)] = e.goal()[j];
  if (kind == EpisodeKind::kExploit && module >= 0) {
    progress_[u] = e.last_progress();
    exploits_.push_back({i + 1, module, e.last_progress()});
  }
  if (scene) {
    float* sc = &scenes_[u * kSceneValues];
    sc[0] = static_cast<float>(scene->ball.x);
    sc[1] = static_cast<float>(scene->ball.y);
    sc[2] = static_cast<float>(scene->distractor.x);
    sc[3] = static_cast<float>(scene->distractor.y);
    grasped_[u] = scene->grasped ? 1 : 0;
  }
  record_interest(i + 1);
}

int PyExplorer::run(const py::object& world, int episodes) {
  check_idle();
  if (ex().pending()) throw py::value_error("run(): an episode is pending: observe() it first");
  const int left = ex().total_episodes() - ex().episode();
  const int n = episodes < 0 ? left : std::min(episodes, left);
  if (py::isinstance<PyWorld>(world)) {
    PyWorld& pw = world.cast<PyWorld&>();
    sim::World& w = pw.world();
    if (!learned() && ex().config().outcome_dim != kEfrOutcomeDim)
      value_error("world", "a curio.World gives 4 outcome values [distractor x, distractor y, "
                           "ball x, ball y]; this explorer expects " +
                               std::to_string(ex().config().outcome_dim));
    const PyWorld::InUse in_use(pw);
    busy_ = true;
    struct Idle {
      bool* b;
      ~Idle() { *b = false; }
    } idle{&busy_};
    auto image = std::make_unique<sim::Image>();
    auto frame = std::make_unique<sim::CameraFrame>();
    float theta[kThetaDim];
    float outcome[kMaxOutcomeDim] = {};
    py::gil_scoped_release release;
    for (int k = 0; k < n; ++k) {
      if (k % 256 == 255) {
        py::gil_scoped_acquire acquire;
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      }
      ex().propose(theta);
      const sim::SceneState s = w.rollout_joint_targets(theta);
      if (learned()) {
        sim::render_scene(s.ball, s.distractor, image.get());
        sim::to_camera_frame(*image, frame.get());
      }
      const app::FinalPositions p{.ball_x = s.ball.x, .ball_y = s.ball.y,
                                  .distractor_x = s.distractor.x, .distractor_y = s.distractor.y};
      if (!app::episode_outcome(p, x_.encoder.get(), frame->data(), outcome)) {
        py::gil_scoped_acquire acquire;
        throw py::value_error("world: the encoder refused episode " + std::to_string(ex().episode()));
      }
      observe_values(outcome, &s);
    }
    return n;
  }
  // A world of the user's: anything with run(theta) -> outcome, or a callable.
  py::object step;
  if (py::hasattr(world, "run")) step = world.attr("run");
  else if (PyCallable_Check(world.ptr())) step = world;
  else type_error("world", "expected a curio.World, an object with run(theta) -> outcome, or a callable");
  for (int k = 0; k < n; ++k) {
    py::object theta = propose();
    observe(step(theta));
  }
  return n;
}

template <typename T>
py::array rows_view(const std::vector<T>& buf, int rows, int width, const py::handle& owner) {
  const auto w = static_cast<py::ssize_t>(width);
  const auto item = static_cast<py::ssize_t>(sizeof(T));
  return readonly_view(buf.data(), {rows, w}, {item * w, item}, owner);
}

int outcome_dim_of(const py::object& outcome_dim) {
  if (outcome_dim.is_none()) return 0;
  const int n = outcome_dim.cast<int>();
  if (n < 1 || n > kMaxOutcomeDim)
    value_error("outcome_dim", "expected 1.." + std::to_string(kMaxOutcomeDim) + " values per outcome");
  return n;
}

}  // namespace

void bind_explorer(py::module_& m) {
  py::class_<PyExplorer>(m, "Explorer", R"doc(
The firmware Explorer (RPE, RGE, MGE of Laversanne-Finot et al., CoRL 2018) driven from Python.

Explorer(algorithm="MGE-EFR", seed=0, episodes=10000, bootstrap=None, sigma=0.05,
         competence_clip=None, window=1000, epsilon=0.1, tie_rule="latest",
         competence_measure="clip", explore="spec", modules=None, outcome_dim=None,
         goals="box", goal_bound=2.5, interest_every=50)

algorithm: one of curio-lab's algorithms ("RPE", "RGE-EFR", "MGE-EFR", "MGE-βVAE" (or
  "MGE-bVAE"), "RGE-βVAE", "MGE-VAE", ...), configured exactly as `curio-lab run` configures
  it (same defaults: bootstrap 100 for EFR and 400 for learned goal spaces, D 1 for EFR and 2
  for learned ones), so the same seed gives curio-lab's archive; or "RGE" / "MGE" / "RPE" with
  `modules`: lists of indices into an outcome vector of your own (outcome_dim values, at most
  10), goals drawn uniformly in [-1, 1]^d ("box") or from a clipped normal ("normal").
explore: "spec" (SPEC §2) or a strategy beyond it ("beyond", ...; docs/beyond.md).

One episode is theta = ex.propose() (49 RBF weights in [-1, 1]), then ex.observe(outcome):
the outcome vector (EFR: [distractor x, distractor y, ball x, ball y]), or for a learned goal
space the 64x64x3 uint8 camera image, which the int8 encoder turns into 10 latents.
ex.run(world, episodes=None) runs episodes in C++ on a curio.World (the GIL released), or
calls world.run(theta) / world(theta) for a world of your own.
)doc")
      .def(py::init([](const std::string& algorithm, uint64_t seed, int episodes,
                       const py::object& bootstrap, double sigma, const py::object& competence_clip,
                       double window, double epsilon, const std::string& tie_rule,
                       const std::string& competence_measure, const std::string& explore,
                       const py::object& modules, const py::object& outcome_dim,
                       const std::string& goals, double goal_bound, int interest_every) {
             return std::make_unique<PyExplorer>(
                 algorithm, seed, episodes, bootstrap.is_none() ? -1 : bootstrap.cast<int>(), sigma,
                 competence_clip.is_none() ? -1.0 : competence_clip.cast<double>(), window, epsilon,
                 tie_rule, competence_measure, explore, modules,
                 outcome_dim_of(outcome_dim), goals, goal_bound,
                 interest_every);
           }),
           py::arg("algorithm") = "MGE-EFR", py::arg("seed") = 0, py::arg("episodes") = 10000,
           py::arg("bootstrap") = py::none(), py::arg("sigma") = 0.05,
           py::arg("competence_clip") = py::none(), py::arg("window") = 1000.0,
           py::arg("epsilon") = 0.1, py::arg("tie_rule") = "latest",
           py::arg("competence_measure") = "clip", py::arg("explore") = "spec",
           py::arg("modules") = py::none(), py::arg("outcome_dim") = py::none(),
           py::arg("goals") = "box", py::arg("goal_bound") = 2.5, py::arg("interest_every") = 50)
      .def("propose", &PyExplorer::propose,
           "theta (float32, 49 values in [-1, 1]) of the current episode; again the same theta "
           "until it is observed.")
      .def("observe", &PyExplorer::observe, py::arg("outcome"),
           "Stores the outcome of the proposed episode: a vector of outcome_dim finite values, "
           "or (learned goal spaces) a 64x64x3 uint8 camera image.")
      .def(
          "run",
          [](PyExplorer& self, const py::object& world, const py::object& episodes) {
            int n = -1;
            if (!episodes.is_none()) {
              if (!PyIndex_Check(episodes.ptr()) || py::isinstance<py::bool_>(episodes))
                type_error("episodes", "expected an int or None");
              const Py_ssize_t v = PyNumber_AsSsize_t(episodes.ptr(), nullptr);
              if (v < 0) value_error("episodes", "expected a number >= 0 (or None: to the end)");
              n = static_cast<int>(std::min<Py_ssize_t>(v, kArchiveCapacity));
            }
            return self.run(world, n);
          },
          py::arg("world"), py::arg("episodes") = py::none(),
           "Runs `episodes` more episodes (default: to the end) on `world`: a curio.World "
           "(in C++, the GIL released; bit for bit curio-lab's run when the seeds agree), an "
           "object with run(theta) -> outcome, or a callable. Returns the episodes run.")
      .def("checksum", &PyExplorer::checksum,
           "FNV-1a (32 bit) of the archive, every episode's regenerated theta then its "
           "outcome: the checksum curio-controller --print-checksum and curio-lab run "
           "--print-checksum print.")
      .def(
          "theta",
          [](const PyExplorer& self, int i) {
            if (i < 0 || i >= self.size()) value_error("i", "no archived episode " + std::to_string(i));
            py::array_t<float> t(kThetaDim);
            self.ex().archive().theta(i, t.mutable_data());
            return t;
          },
          py::arg("i"), "theta of archived episode i, regenerated from its recipe (a copy).")
      .def(
          "thetas",
          [](const PyExplorer& self) {
            py::array_t<float> t({self.size(), kThetaDim});
            for (int i = 0; i < self.size(); ++i) self.ex().archive().theta(i, t.mutable_data(i, 0));
            return t;
          },
          "Every archived theta, (episodes, 49) float32: regenerated (the archive stores 4-byte "
          "recipes, not theta), so this is a copy.")
      .def(
          "verdicts",
          [](const PyExplorer& self, double min_t, double min_relative_interest) {
            return self.verdicts(min_t, min_relative_interest);
          },
          py::arg("min_t") = 3.0, py::arg("min_relative_interest") = 0.1,
          "Controllable-feature verdicts per module, as curio-lab computes them (see "
          "curio.controllability).")
      .def_property_readonly("outcomes",
                             [](const py::object& self_obj) {
                               const auto& self = self_obj.cast<const PyExplorer&>();
                               const Archive& a = self.ex().archive();
                               return readonly_view(a.outcome_column(0), {a.size(), a.outcome_dim()},
                                                    {sizeof(float), sizeof(float) * Archive::kCapacity},
                                                    self_obj);
                             },
                             "Archived outcomes, (episodes, outcome_dim) float32: a read-only view "
                             "of the archive's columns (no copy).")
      .def_property_readonly("kinds",
                             [](const py::object& o) {
                               const auto& s = o.cast<const PyExplorer&>();
                               return readonly_view(s.kinds_.data(), {s.size()}, {1}, o);
                             },
                             "Each episode's kind (uint8 view): index into KIND_NAMES.")
      .def_property_readonly("choices",
                             [](const py::object& o) {
                               const auto& s = o.cast<const PyExplorer&>();
                               return readonly_view(s.modules_.data(), {s.size()}, {1}, o);
                             },
                             "Each episode's goal module (int8 view), -1 for random episodes.")
      .def_property_readonly("goals",
                             [](const py::object& o) {
                               const auto& s = o.cast<const PyExplorer&>();
                               return rows_view(s.goals_, s.size(), s.goal_width(), o);
                             },
                             "Each episode's goal, (episodes, widest module) float32 view, NaN "
                             "where the module has fewer dims and for random episodes.")
      .def_property_readonly("progress",
                             [](const py::object& o) {
                               const auto& s = o.cast<const PyExplorer&>();
                               return readonly_view(s.progress_.data(), {s.size()}, {4}, o);
                             },
                             "Learning progress p of each exploit episode (float32 view), NaN "
                             "for the others.")
      .def_property_readonly("interest",
                             [](const py::object& o) {
                               const auto& s = o.cast<const PyExplorer&>();
                               const int k = s.ex().n_modules();
                               return rows_view(s.interest_, k ? s.interest_samples() : 0, k, o);
                             },
                             "Every module's interest |cp|, one row every interest_every "
                             "episodes (float32 view; see interest_episodes).")
      .def_property_readonly("interest_episodes",
                             [](const py::object& o) {
                               const auto& s = o.cast<const PyExplorer&>();
                               return readonly_view(s.interest_episodes_.data(), {s.interest_samples()}, {4}, o);
                             },
                             "Episode counts of the interest rows (int32 view).")
      .def_property_readonly("scenes",
                             [](const py::object& o) {
                               const auto& s = o.cast<const PyExplorer&>();
                               return rows_view(s.scenes_, s.size(), kSceneValues, o);
                             },
                             "Final [ball x, ball y, distractor x, distractor y] of each episode "
                             "run on a curio.World (float32 view; NaN for ask/tell episodes).")
      .def_property_readonly("grasped",
                             [](const py::object& o) {
                               const auto& s = o.cast<const PyExplorer&>();
                               return readonly_view(reinterpret_cast<const bool*>(s.grasped_.data()),
                                                    {s.size()}, {1}, o);
                             },
                             "Whether each episode run on a curio.World ended with the ball grasped (bool view).")
      .def_property_readonly(
          "module_choices",
          [](const PyExplorer& s) {
            py::array_t<int64_t> c(s.ex().n_modules());
            for (int k = 0; k < s.ex().n_modules(); ++k) c.mutable_at(k) = 0;
            for (const auto& e : s.exploits_) c.mutable_at(e.module) += 1;
            return c;
          },
          "How often each module was chosen (exploits per module).")
      .def_property_readonly("algorithm", &PyExplorer::algorithm)
      .def_property_readonly("seed", [](const PyExplorer& s) { return s.ex().config().seed; })
      .def_property_readonly("episode", [](const PyExplorer& s) { return s.ex().episode(); },
                             "Index of the current episode (= episodes archived).")
      .def_property_readonly("total_episodes", [](const PyExplorer& s) { return s.ex().total_episodes(); },
                             "bootstrap + episodes.")
      .def_property_readonly("bootstrap", [](const PyExplorer& s) { return s.ex().config().n_bootstrap; })
      .def_property_readonly("done", [](const PyExplorer& s) { return s.ex().done(); })
      .def_property_readonly("pending", [](const PyExplorer& s) { return s.ex().pending(); })
      .def_property_readonly("kind", [](const PyExplorer& s) { return to_string(s.ex().kind()); },
                             "Kind of the current episode: bootstrap, random, explore, exploit.")
      .def_property_readonly("module", [](const PyExplorer& s) { return s.ex().module(); },
                             "Module of the current step (-1 before the first).")
      .def_property_readonly("goal",
                             [](const PyExplorer& s) {
                               py::array_t<float> g(s.ex().goal_dim());
                               for (int j = 0; j < s.ex().goal_dim(); ++j) g.mutable_at(j) = s.ex().goal()[j];
                               return g;
                             },
                             "Goal of the current step (a copy).")
      .def_property_readonly("outcome_dim", [](const PyExplorer& s) { return s.ex().config().outcome_dim; })
      .def_property_readonly("n_modules", [](const PyExplorer& s) { return s.ex().n_modules(); })
      .def_property_readonly("module_names", &PyExplorer::module_names)
      .def_property_readonly(
          "module_dims",
          [](const PyExplorer& s) {
            std::vector<std::vector<int>> d;
            for (int k = 0; k < s.ex().n_modules(); ++k) {
              const GoalModule& g = s.ex().goal_module(k);
              d.emplace_back(g.dims, g.dims + g.n_dims);
            }
            return d;
          },
          "Outcome indices of each module (learned goal spaces: latents in KL order).")
      .def_property_readonly("learned", &PyExplorer::learned,
                             "Whether observe() takes camera images (a learned goal space).")
      .def_property_readonly(
          "current_interest",
          [](const PyExplorer& s) {
            py::array_t<float> v(s.ex().n_modules());
            for (int k = 0; k < s.ex().n_modules(); ++k) v.mutable_at(k) = s.ex().interest(k);
            return v;
          },
          "Every module's interest now.")
      .def_property_readonly("counters", [](const PyExplorer& s) {
        const ExplorerCounters& c = s.ex().counters();
        py::dict d;
        d["proposals"] = c.proposals;
        d["repeated_proposals"] = c.repeated_proposals;
        d["observations"] = c.observations;
        d["out_of_order"] = c.out_of_order;
        d["non_finite_outcomes"] = c.non_finite_outcomes;
        d["nn_queries"] = c.nn_queries;
        d["random_fallbacks"] = c.random_fallbacks;
        d["steps"] = c.steps;
        return d;
      })
      .def("__len__", &PyExplorer::size)
      .def("__repr__", [](const PyExplorer& s) {
        return "curio.Explorer('" + s.algorithm() + "', seed=" + std::to_string(s.ex().config().seed) +
               ", episode " + std::to_string(s.ex().episode()) + "/" +
               std::to_string(s.ex().total_episodes()) + ")";
      });
  m.attr("KIND_NAMES") = py::make_tuple("none", "bootstrap", "random", "explore", "exploit");

  m.def(
      "controllability",
      [](const py::object& exploit_episodes, const py::object& exploit_modules,
         const py::object& exploit_progress, const py::object& interest,
         const py::object& interest_episodes, int first_episode, int last_episode, double min_t,
         double min_relative_interest) {
        const auto ep = py::array_t<int64_t, py::array::c_style | py::array::forcecast>::ensure(exploit_episodes);
        const auto mo = py::array_t<int64_t, py::array::c_style | py::array::forcecast>::ensure(exploit_modules);
        const auto pr = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(exploit_progress);
        const auto in = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(interest);
        const auto ie = py::array_t<int64_t, py::array::c_style | py::array::forcecast>::ensure(interest_episodes);
        if (!ep || ep.ndim() != 1) value_error("exploit_episodes", "expected a 1-D integer array");
        if (!mo || mo.ndim() != 1 || mo.shape(0) != ep.shape(0))
          value_error("exploit_modules", "expected a 1-D integer array as long as exploit_episodes");
        if (!pr || pr.ndim() != 1 || pr.shape(0) != ep.shape(0))
          value_error("exploit_progress", "expected a 1-D array as long as exploit_episodes");
        if (!in || in.ndim() != 2) value_error("interest", "expected a 2-D array (samples, modules)");
        if (!ie || ie.ndim() != 1 || ie.shape(0) != in.shape(0))
          value_error("interest_episodes", "expected a 1-D array with one episode count per interest row");
        const auto k = in.shape(1);
        std::vector<lab::ProgressSample> ex;
        for (py::ssize_t i = 0; i < ep.shape(0); ++i) {
          if (mo.at(i) < 0 || mo.at(i) >= k)
            value_error("exploit_modules", "module " + std::to_string(mo.at(i)) + " has no interest column");
          ex.push_back({static_cast<int>(ep.at(i)), static_cast<int>(mo.at(i)), pr.at(i)});
        }
        std::vector<std::vector<float>> rows;
        for (py::ssize_t s = 0; s < in.shape(0); ++s)
          rows.emplace_back(in.data(s, 0), in.data(s, 0) + k);
        std::vector<int> eps(ie.data(), ie.data() + ie.shape(0));
        return verdict_dict(lab::classify_modules(ex, rows, eps, first_episode, last_episode,
                                                  {min_t, min_relative_interest}));
      },
      py::arg("exploit_episodes"), py::arg("exploit_modules"), py::arg("exploit_progress"),
      py::arg("interest"), py::arg("interest_episodes"), py::arg("first_episode"),
      py::arg("last_episode"), py::arg("min_t") = 3.0, py::arg("min_relative_interest") = 0.1,
      R"doc(The controllable-feature verdict of paper §4.3, as curio-lab computes it.

For each module k, over the exploits in the second half of (first_episode, last_episode]:
t_k = mean(p) / (std(p) / sqrt(n)) of the learning progress p, and relative interest =
mean |cp_k| / max_j mean |cp_j|; controllable iff t_k >= min_t and relative interest >=
min_relative_interest. Returns a dict of arrays, one entry per module: controllable, t,
relative_interest, mean_progress, mean_interest, exploits.)doc");
}

}  // namespace curio::python
