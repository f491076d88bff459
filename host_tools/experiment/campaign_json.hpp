// A campaign's configuration as JSON (summary.json's "campaign" block, task manifests) and
// back: the identity of a campaign, which its task folders must share to be merged.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "host_tools/experiment/campaign_config.hpp"

namespace curio::lab {

// Everything that decides the campaign's results (not threads, output folder or verbosity).
nlohmann::json campaign_to_json(const CampaignConfig& config);

// The inverse of campaign_to_json; nullopt with *error when a field is missing or unknown.
std::optional<CampaignConfig> campaign_from_json(const nlohmann::json& j, std::string* error);

// "episodes: 2000 vs 10000", one line per field that differs (empty: the same campaign).
std::vector<std::string> campaign_differences(const nlohmann::json& a, const nlohmann::json& b);

}  // namespace curio::lab
