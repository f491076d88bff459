// The exploration options of every program that explores (exploration_options.hpp).
#include "host_tools/experiment/exploration_options.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "host_tools/experiment/explore_strategies.hpp"
#include "host_tools/cli/command_line.hpp"

namespace curio::lab {

namespace {

// "0.05,0.1" → σ values; false with *problem naming the first that is not a number.
bool parse_sigmas(const std::string& text, std::vector<double>* sigmas, std::string* problem) {
  sigmas->clear();
  std::stringstream ss(text);
  for (std::string s; std::getline(ss, s, ',');) {
    if (s.empty()) continue;
    try {
      size_t used = 0;
      const double v = std::stod(s, &used);
      if (used != s.size()) throw std::invalid_argument(s);
      sigmas->push_back(v);
    } catch (const std::exception&) {
      *problem = "--noise: bad σ '" + s + "' (use e.g. 0.05 or 0.05,0.1)";
      return false;
    }
  }
  return true;
}

}  // namespace

void add_exploration_options(CLI::App* app, ExplorationOptions* o, ExplorationSet set) {
  if (set != ExplorationSet::kStrategyOnly) {
    app->add_option("--noise", o->noise,
                    set == ExplorationSet::kCampaign
                        ? "Exploration noise σ on θ; several: 0.05,0.1"
                        : "Exploration noise σ on θ (a finite number ≥ 0)")
        ->capture_default_str();
    app->add_option("--bootstrap", o->bootstrap,
                    "Random episodes first (default: 100 for EFR, 400 for learned goal spaces)")
        ->check(curio::cli::kNonNegative);
    app->add_option("--competence-clip", o->competence_clip,
                    "D of SPEC §2.5 (default: 1 for EFR, reproducing the archived runs; 2 for "
                    "learned goal spaces)")
        ->check(curio::cli::kPositive);
    app->add_option("--competence", o->competence,
                    "How D enters the competence of SPEC §2.5: clip (-min(|g-r|, D), SPEC as "
                    "written) or scale (-|g-r|/D, explauto's competence_dist as the reference "
                    "ran it)")
        ->capture_default_str();
    app->add_option("--window", o->window, "W of SPEC §2.5 (interest smoothing, episodes)")
        ->capture_default_str();
    app->add_option("--epsilon", o->epsilon, "Share of uniform module choice")
        ->capture_default_str();
    app->add_option("--tie-rule", o->tie_rule,
                    "Which archive entry wins a 1-NN tie: latest (tracks the reference "
                    "implementation; docs/reproduction.md) or earliest")
        ->capture_default_str();
  }
  app->add_option("--explore", o->explore,
                  "Goal-exploration strategy of the goal algorithms: spec (SPEC §2, the "
                  "reproduction), beyond (frontier goals in half the steps and a σ ladder "
                  "×(1,2,2,4) over a step's 4 explore episodes; docs/beyond.md), or one of its "
                  "ablations: beyond-without-frontier, beyond-without-ladder, beyond-flat-sigma")
      ->capture_default_str();
}

bool apply_exploration_options(const ExplorationOptions& o, ExplorationSet set,
                               CampaignConfig* c, std::string* problem) {
  if (!find_explore_strategy(o.explore)) {
    *problem = "--explore: unknown strategy '" + o.explore + "' (known: " +
               explore_strategy_names() + ")";
    return false;
  }
  c->explore = o.explore;
  if (set == ExplorationSet::kStrategyOnly) return true;
  if (!parse_sigmas(o.noise, &c->sigmas, problem)) return false;
  if (set == ExplorationSet::kOneRun && c->sigmas.size() != 1) {
    *problem = "--noise: one run takes one σ (got '" + o.noise + "'; curio-lab runs several)";
    return false;
  }
  c->bootstrap = o.bootstrap;
  c->competence_clip = o.competence_clip;
  c->window = o.window;
  c->epsilon = o.epsilon;
  if (const auto m = parse_competence_measure(o.competence)) {
    c->competence_measure = *m;
  } else {
    *problem = "unknown --competence '" + o.competence + "' (clip or scale)";
    return false;
  }
  if (const auto t = parse_tie_rule(o.tie_rule)) {
    c->tie_rule = *t;
  } else {
    *problem = "unknown --tie-rule '" + o.tie_rule + "' (latest or earliest)";
    return false;
  }
  return true;
}

}  // namespace curio::lab
