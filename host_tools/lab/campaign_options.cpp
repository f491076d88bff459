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

}  // namespace

void add_campaign_options(CLI::App* sub, CampaignOptions& o) {
  CampaignConfig& c = o.config;
  sub->add_option("--algos", o.algos,
                  "Comma-separated algorithms: RPE, RGE-EFR, MGE-EFR, RGE-βVAE, MGE-βVAE, "
                  "MGE-βVAE-10, RGE-VAE, MGE-VAE, MGE-VAE-10 (βVAE may be spelt bVAE)")
      ->capture_default_str();
  sub->add_option("--seeds", o.seeds, "Seeds: 0-14, 0,3,7 or 1-3,8")->capture_default_str();
  sub->add_option("--physics", o.physics, "kinematic (the paper's model) or ode (the ODE arm)")
      ->capture_default_str();
  sub->add_option("--episodes", c.episodes, "Exploration episodes after the bootstrap")
      ->capture_default_str();
  add_exploration_options(sub, &o.exploration, ExplorationSet::kCampaign);
  sub->add_option("--grasp-radius", c.world.grasp_radius, "Grasp radius")->capture_default_str();
  sub->add_option("--distractor-noise", c.world.distractor_noise,
                  "Distractor random-walk std per step")
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
  if (!sim::parse_physics(o.physics, &c->physics)) {
    *problem = "unknown --physics '" + o.physics + "' (kinematic or ode)";
    return false;
  }
  if (!apply_exploration_options(o.exploration, ExplorationSet::kCampaign, c, problem)) return false;
  const auto problems = validate_campaign(*c);
  if (problems.empty()) return true;
  *problem = problems.front();
  return false;
}

}  // namespace curio::lab
