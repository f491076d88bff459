#include "firmware/explore/explorer.hpp"

#include <cmath>

#include "firmware/explore/module_choice.hpp"
#include "firmware/explore/nearest_neighbour.hpp"
#include "firmware/explore/schedule.hpp"

namespace curio {

static_assert(sizeof(ExplorerConfig{}.sigma_ladder) / sizeof(float) ==
                  static_cast<size_t>(ThetaGenerator::kLadderSteps),
              "the config's σ ladder is the θ generator's");

namespace {

// Goal module k as `config` describes it (init and rebase build modules the same way).
GoalModule module_of(const ExplorerConfig& config, int k) {
  GoalModule m;
  m.n_dims = config.modules[k].n_dims;
  for (int j = 0; j < kMaxOutcomeDim; ++j) m.dims[j] = config.modules[k].dims[j];
  m.goal_kind = config.goal_kind;
  m.goal_bound = config.goal_bound;
  m.goal_scale = config.goal_scale;
  return m;
}

}  // namespace

Status Explorer::init(const ExplorerConfig& config) {
  initialised_ = false;
  const Status s = validate(config);
  if (s != Status::kOk) return s;
  config_ = config;
  ThetaGenerator generator;
  generator.reset(config.seed, config.sigma,
                  has_sigma_ladder(config) ? config.sigma_ladder : nullptr);
  archive_.reset(config.outcome_dim, generator);
  n_modules_ = config.algorithm == Algorithm::kRpe ? 0 : config.n_modules;
  for (int k = 0; k < kMaxModules; ++k) {
    modules_[k] = GoalModule{};
    distinct_[k].reset();
    if (k < n_modules_) modules_[k] = module_of(config, k);
  }
  interest_.reset(n_modules_ > 0 ? n_modules_ : 1, config.competence_cap, config.window,
                  config.competence_measure);
  choice_rng_.reseed(config.seed, kStreamModuleChoice);
  goal_rng_.reseed(config.seed, kStreamGoal);
  frontier_rng_.reseed(config.seed, kStreamFrontier);
  frontier_.reset(modules_, n_modules_);
  random_thetas_ = 0;
  noise_vectors_ = 0;
  for (float& g : goal_) g = 0.0f;
  counters_ = ExplorerCounters{};
  total_episodes_ = config.n_bootstrap + config.n_episodes;
  module_ = -1;
  step_nn_ = -1;
  source_ = -1;
  directed_source_ = -1;
  directed_step_ = false;
  last_progress_ = 0.0f;
  pending_ = false;
  initialised_ = true;
  return Status::kOk;
}

Status Explorer::rebase(const ExplorerConfig& c, const float* outcomes, const float* progress) {
  if (!initialised_) return Status::kNotInitialised;
  if (outcomes == nullptr || progress == nullptr) return Status::kInvalidArgument;
  const Status v = validate(c);
  if (v != Status::kOk) return v;
  const ExplorerConfig& o = config_;
  const bool same_run = c.seed == o.seed && c.sigma == o.sigma &&
                        c.competence_cap == o.competence_cap && c.window == o.window &&
                        c.epsilon == o.epsilon && c.competence_measure == o.competence_measure &&
                        c.n_bootstrap == o.n_bootstrap && c.n_episodes == o.n_episodes &&
                        c.outcome_dim == o.outcome_dim && c.tie_rule == o.tie_rule &&
                        c.requery_exploit == o.requery_exploit &&
                        c.algorithm != Algorithm::kRpe && o.algorithm != Algorithm::kRpe;
  const int e = episode();
  const bool between_steps =
      !pending_ && (e < o.n_bootstrap || (e - o.n_bootstrap) % kEpisodesPerStep == 0);
  if (!same_run || !between_steps || c.n_modules < 1) return Status::kInvalidArgument;
  const int n = archive_.size();
  for (int i = 0; i < n * c.outcome_dim; ++i)
    if (!std::isfinite(outcomes[i])) return Status::kInvalidArgument;
  for (int k = 0; k < c.n_modules; ++k)
    if (!std::isfinite(progress[k])) return Status::kInvalidArgument;

  config_ = c;
  n_modules_ = c.n_modules;
  for (int i = 0; i < n; ++i) archive_.set_outcome(i, outcomes + i * c.outcome_dim);
  for (int k = 0; k < kMaxModules; ++k) {
    modules_[k] = GoalModule{};
    distinct_[k].reset();
    if (k >= n_modules_) continue;
    modules_[k] = module_of(c, k);
  }
  frontier_.reset(modules_, n_modules_);
  for (int k = 0; k < n_modules_; ++k) {
    float projected[kMaxOutcomeDim];
    for (int i = 0; i < n; ++i) {
      modules_[k].project(outcomes + i * c.outcome_dim, projected);
      distinct_[k].observe(projected, modules_[k].n_dims);
      if (c.frontier_share > 0.0f) frontier_.observe(k, projected);
    }
  }
  interest_.reset(n_modules_, c.competence_cap, c.window, c.competence_measure);
  interest_.restart(progress);
  module_ = -1;
  step_nn_ = -1;
  source_ = -1;
  directed_source_ = -1;
  directed_step_ = false;
  return Status::kOk;
}

Status Explorer::explore_around(int source) {
  if (!initialised_) return Status::kNotInitialised;
  const int e = episode();
  const bool starts_step = !pending_ && !done() && kind_of(e) == EpisodeKind::kExplore &&
                           (e - config_.n_bootstrap) % kEpisodesPerStep == 0;
  if (!starts_step || source < 0 || source >= e) return Status::kInvalidArgument;
  directed_source_ = source;
  return Status::kOk;
}

EpisodeKind Explorer::kind_of(int e) const {
  if (!initialised_ || e >= total_episodes_) return EpisodeKind::kNone;
  if (e < config_.n_bootstrap) return EpisodeKind::kBootstrap;
  if (config_.algorithm == Algorithm::kRpe) return EpisodeKind::kRandom;
  return (e - config_.n_bootstrap) % kEpisodesPerStep < kExploreEpisodesPerStep
             ? EpisodeKind::kExplore
             : EpisodeKind::kExploit;
}

EpisodeKind Explorer::kind() const {
  return kind_of(episode());
}

void Explorer::random_theta() {
  pending_recipe_ = ThetaRecipe::random(random_thetas_);
  archive_.generator().random_theta(pending_recipe_.draw, pending_theta_);
  ++random_thetas_;
}

int Explorer::query(int k) {
  if (!distinct_[k].has_two()) return -1;
  ++counters_.nn_queries;
  return nearest_neighbour(archive_, modules_[k].dims, modules_[k].n_dims, goal_, config_.tie_rule);
}

void Explorer::start_step() {
  directed_step_ = directed_source_ >= 0;
  if (directed_step_) {
    module_ = -1;
    step_nn_ = directed_source_;
    directed_source_ = -1;
    archive_.theta(step_nn_, step_theta_);
    ++counters_.steps;
    return;
  }
  float interests[kMaxModules];
  for (int k = 0; k < n_modules_; ++k) interests[k] = interest_.interest(k);
  module_ = choose_module(interests, n_modules_, config_.epsilon, choice_rng_);
  const bool frontier = config_.frontier_share > 0.0f &&
                        frontier_rng_.uniform01() < config_.frontier_share &&
                        frontier_.sample(module_, frontier_rng_, goal_);
  if (!frontier) modules_[module_].sample_goal(goal_rng_, goal_);
  step_nn_ = query(module_);
  if (step_nn_ >= 0) archive_.theta(step_nn_, step_theta_);
  ++counters_.steps;
}

Status Explorer::propose(float theta[kThetaDim]) {
  if (!initialised_) return Status::kNotInitialised;
  if (theta == nullptr) return Status::kInvalidArgument;
  if (done()) return Status::kDone;
  if (!pending_) {
    const int e = episode();
    switch (kind_of(e)) {
      case EpisodeKind::kExplore:
        if ((e - config_.n_bootstrap) % kEpisodesPerStep == 0) start_step();
        source_ = step_nn_;
        if (source_ >= 0) {
          for (int i = 0; i < kThetaDim; ++i) pending_theta_[i] = step_theta_[i];
          pending_recipe_ = ThetaRecipe::explore(source_, noise_vectors_);
          archive_.generator().add_noise(pending_recipe_.draw, pending_theta_);
          ++noise_vectors_;
        }
        break;
      case EpisodeKind::kExploit:
        source_ = config_.requery_exploit && !directed_step_ ? query(module_) : step_nn_;
        if (source_ == step_nn_ && source_ >= 0) {
          for (int i = 0; i < kThetaDim; ++i) pending_theta_[i] = step_theta_[i];
          pending_recipe_ = archive_.recipe(source_);
        } else if (source_ >= 0) {
          archive_.theta(source_, pending_theta_);
          pending_recipe_ = archive_.recipe(source_);
        }
        break;
      default:  // bootstrap, RPE
        source_ = -1;
        random_theta();
        break;
    }
    const EpisodeKind k = kind_of(e);
    if (source_ < 0 && (k == EpisodeKind::kExplore || k == EpisodeKind::kExploit)) {
      ++counters_.random_fallbacks;
      random_theta();
    }
    pending_ = true;
    ++counters_.proposals;
  } else {
    ++counters_.repeated_proposals;
  }
  for (int i = 0; i < kThetaDim; ++i) theta[i] = pending_theta_[i];
  return Status::kOk;
}

Status Explorer::observe(const float* outcome) {
  if (!initialised_) return Status::kNotInitialised;
  if (!pending_) {
    ++counters_.out_of_order;
    return Status::kNoPendingEpisode;
  }
  if (outcome == nullptr) return Status::kInvalidArgument;
  for (int d = 0; d < config_.outcome_dim; ++d) {
    if (!std::isfinite(outcome[d])) {
      ++counters_.non_finite_outcomes;
      return Status::kNonFiniteOutcome;
    }
  }
  const EpisodeKind k = kind();
  const Status s = archive_.append(pending_recipe_, outcome);
  if (s != Status::kOk) {
    ++counters_.archive_rejections;
    return s;
  }
  float projected[kMaxOutcomeDim];
  for (int m = 0; m < n_modules_; ++m) {
    modules_[m].project(outcome, projected);
    distinct_[m].observe(projected, modules_[m].n_dims);
    if (config_.frontier_share > 0.0f) frontier_.observe(m, projected);
  }
  if (k == EpisodeKind::kExploit && !directed_step_) {
    modules_[module_].project(outcome, projected);
    last_progress_ = interest_.update(module_, goal_, projected, modules_[module_].n_dims);
    frontier_.step_done(module_);
  }
  pending_ = false;
  ++counters_.observations;
  return Status::kOk;
}

}  // namespace curio
