#include "host_tools/lab/campaign_options.hpp"

#include <sstream>
#include <stdexcept>
#include <vector>

#include "host_tools/cli/command_line.hpp"

namespace curio::lab {

namespace {

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, sep);)
    if (!item.empty()) out.push_back(item);
  return out;
}

// "0.05,0.1" → σ values; false with *problem naming the first that is not a number.
bool parse_sigmas(const std::string& text, std::vector<double>* sigmas, std::string* problem) {
  sigmas->clear();
  for (const auto& s : split(text, ',')) {
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

void add_campaign_options(CLI::App* sub, CampaignOptions& o) {
  CampaignConfig& c = o.config;
  sub->add_option("--algos", o.algos,
                  "Comma-separated algorithms: RPE, RGE-EFR, MGE-EFR, RGE-βVAE, MGE-βVAE, "
                  "MGE-βVAE-10, RGE-VAE, MGE-VAE, MGE-VAE-10 (βVAE may be spelt bVAE)")
      ->capture_default_str();
  sub->add_option("--seeds", o.seeds, "Seeds: 0-14, 0,3,7 or 1-3,8")->capture_default_str();
  sub->add_option("--noise", o.noise, "Exploration noise σ on θ; several: 0.05,0.1")
      ->capture_default_str();
  sub->add_option("--physics", o.physics, "kinematic (the paper's model) or ode (the ODE arm)")
      ->capture_default_str();
  sub->add_option("--episodes", c.episodes, "Exploration episodes after the bootstrap")
      ->capture_default_str();
  sub->add_option("--bootstrap", c.bootstrap,
                  "Random episodes first (default: 100 for EFR, 400 for learned goal spaces)")
      ->check(curio::cli::kNonNegative);
  sub->add_option("--competence-clip", c.competence_clip,
                  "D of SPEC §2.5 (default: 1 for EFR, reproducing the archived runs; 2 for "
                  "learned goal spaces)")
      ->check(curio::cli::kPositive);
  sub->add_option(
         "--competence", o.competence,
         "How D enters the competence of SPEC §2.5: clip (-min(|g-r|, D), SPEC as "
         "written) or scale (-|g-r|/D, explauto's competence_dist as the reference ran it)")
      ->capture_default_str();
  sub->add_option("--window", c.window, "W of SPEC §2.5 (interest smoothing)")
      ->capture_default_str();
  sub->add_option("--epsilon", c.epsilon, "Share of uniform module choice")->capture_default_str();
  sub->add_option("--grasp-radius", c.world.grasp_radius, "Grasp radius")->capture_default_str();
  sub->add_option("--distractor-noise", c.world.distractor_noise,
                  "Distractor random-walk std per step")
      ->capture_default_str();
  sub->add_option("--tie-rule", o.tie_rule,
                  "Which archive entry wins a 1-NN tie: latest (tracks the reference "
                  "implementation; docs/reproduction.md) or earliest")
      ->capture_default_str();
  sub->add_option("--explore", c.explore,
                  "Goal-exploration strategy of the goal algorithms: spec (SPEC §2, the "
                  "reproduction), beyond (frontier goals in half the steps and a σ ladder "
                  "×(1,2,2,4) over a step's 4 explore episodes; docs/beyond.md), or one of its "
                  "ablations: beyond-without-frontier, beyond-without-ladder, beyond-flat-sigma")
      ->capture_default_str();
  sub->add_option("--threads", c.threads, "Worker threads (0: all cores)")->capture_default_str();
}

bool build_campaign(const CampaignOptions& o, CampaignConfig* c, std::string* problem) {
  *c = o.config;
  c->algorithms = split(o.algos, ',');
  for (auto& name : c->algorithms)  // canonical names (MGE-bVAE → MGE-βVAE) for grouping
    if (const auto algo = find_algorithm(name)) name = algo->name;
  std::string err;
  if (auto seeds = parse_seeds(o.seeds, &err)) {
    c->seeds = *seeds;
  } else {
    *problem = "--seeds: " + err;
    return false;
  }
  if (!parse_sigmas(o.noise, &c->sigmas, problem)) return false;
  if (!sim::parse_physics(o.physics, &c->physics)) {
    *problem = "unknown --physics '" + o.physics + "' (kinematic or ode)";
    return false;
  }
  if (const auto t = parse_tie_rule(o.tie_rule)) {
    c->tie_rule = *t;
  } else {
    *problem = "unknown --tie-rule '" + o.tie_rule + "' (earliest or latest)";
    return false;
  }
  if (const auto m = parse_competence_measure(o.competence)) {
    c->competence_measure = *m;
  } else {
    *problem = "unknown --competence '" + o.competence + "' (clip or scale)";
    return false;
  }
  const auto problems = validate_campaign(*c);
  if (problems.empty()) return true;
  *problem = problems.front();
  return false;
}

}  // namespace curio::lab
