#include "host_tools/experiment/campaign_json.hpp"

#include <algorithm>
#include <climits>

namespace curio::lab {
using nlohmann::json;

json campaign_to_json(const CampaignConfig& c) {
  json j = {{"algorithms", c.algorithms},
          {"seeds", c.seeds},
          {"sigmas", c.sigmas},
          {"physics", sim::physics_name(c.physics)},
          {"episodes", c.episodes},
          {"bootstrap", c.bootstrap},
          {"competence_clip", c.competence_clip},
          {"window", c.window},
          {"epsilon", c.epsilon},
          {"competence", to_string(c.competence_measure)},
          {"tie_rule", c.tie_rule == TieRule::kEarliest ? "earliest" : "latest"},
          {"grasp_radius", c.world.grasp_radius},
          {"distractor_noise", c.world.distractor_noise}};
  // Written only when it is not SPEC's: campaigns from before the strategies keep their identity.
  if (c.explore != "spec") j["explore"] = c.explore;
  return j;
}

std::optional<CampaignConfig> campaign_from_json(const json& j, std::string* error) {
  CampaignConfig c;
  // Whole numbers as JSON writes them: nlohmann alone would wrap a seed of -1 to 2^64 - 1, an
  // episode count of 2^32 + 5 to 5 and cut 2.5 to 2. Seeds are 64-bit; counts are ints.
  const auto whole = [&](const char* key, bool seed) {
    const json& v = j.at(key);
    const auto ok = [&](const json& x) {
      if (seed || x.is_number_unsigned())
        return x.is_number_unsigned() && (seed || x.get<unsigned long long>() <= INT_MAX);
      return x.is_number_integer() && x.get<long long>() >= INT_MIN &&
             x.get<long long>() <= INT_MAX;
    };
    bool good = v.is_array() ? std::all_of(v.begin(), v.end(), ok) : ok(v);
    if (!good) *error = std::string("\"") + key + "\" is " + v.dump() +
                        (seed ? ", not whole numbers >= 0" : ", not a whole number within int");
    return good;
  };
  try {
    if (!whole("seeds", true) || !whole("episodes", false) || !whole("bootstrap", false))
      return std::nullopt;
    c.algorithms = j.at("algorithms").get<std::vector<std::string>>();
    c.seeds = j.at("seeds").get<std::vector<uint64_t>>();
    c.sigmas = j.at("sigmas").get<std::vector<double>>();
    const auto physics = j.at("physics").get<std::string>();
    if (!sim::parse_physics(physics, &c.physics)) {
      *error = "unknown physics '" + physics + "'";
      return std::nullopt;
    }
    c.episodes = j.at("episodes").get<int>();
    c.bootstrap = j.at("bootstrap").get<int>();
    c.competence_clip = j.at("competence_clip").get<double>();
    c.window = j.at("window").get<double>();
    c.epsilon = j.at("epsilon").get<double>();
    const auto competence = j.at("competence").get<std::string>();
    const auto measure = parse_competence_measure(competence);
    const auto tie = parse_tie_rule(j.at("tie_rule").get<std::string>());
    if (!measure || !tie) {
      *error = "unknown competence measure or tie rule";
      return std::nullopt;
    }
    c.competence_measure = *measure;
    c.tie_rule = *tie;
    c.world.grasp_radius = j.at("grasp_radius").get<double>();
    c.world.distractor_noise = j.at("distractor_noise").get<double>();
    c.explore = j.value("explore", std::string("spec"));
  } catch (const json::exception& e) {
    *error = std::string("bad campaign block: ") + e.what();
    return std::nullopt;
  }
  if (const auto problems = validate_campaign(c); !problems.empty()) {
    *error = "bad campaign block: " + problems.front();
    return std::nullopt;
  }
  return c;
}

std::vector<std::string> campaign_differences(const json& a, const json& b) {
  std::vector<std::string> out;
  for (const auto& [key, value] : a.items())
    if (!b.contains(key))
      out.push_back(key + ": " + value.dump() + " vs (none)");
    else if (b[key] != value)
      out.push_back(key + ": " + value.dump() + " vs " + b[key].dump());
  for (const auto& [key, value] : b.items())
    if (!a.contains(key)) out.push_back(key + ": (none) vs " + value.dump());
  return out;
}

}  // namespace curio::lab
