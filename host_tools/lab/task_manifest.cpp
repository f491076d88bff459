#include "host_tools/lab/task_manifest.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include "host_tools/experiment/campaign_json.hpp"
#include "host_tools/experiment/report.hpp"

namespace curio::lab {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {
constexpr const char* kFormat = "curio-lab task";

// A whole number within [lo, hi] as JSON writes it (nlohmann's get<int> would wrap 2^40).
bool whole_in(const json& v, long long lo, unsigned long long hi) {
  if (v.is_number_unsigned()) return v.get<unsigned long long>() <= hi;
  if (v.is_number_integer()) {
    const long long x = v.get<long long>();
    return x >= lo && (x < 0 || static_cast<unsigned long long>(x) <= hi);
  }
  return false;
}
}  // namespace

std::vector<size_t> task_runs(size_t runs_in_campaign, int task, int tasks) {
  std::vector<size_t> out;
  if (tasks <= 0 || task < 0 || task >= tasks) return out;
  for (size_t i = static_cast<size_t>(task); i < runs_in_campaign; i += static_cast<size_t>(tasks))
    out.push_back(i);
  return out;
}

std::string manifest_path(const std::string& dir) {
  return (fs::path(dir) / "manifest.json").string();
}

json manifest_json(const CampaignConfig& config, int task, int tasks) {
  const auto specs = expand_runs(config);
  json runs = json::array();
  for (size_t i : task_runs(specs.size(), task, tasks))
    runs.push_back({{"index", i}, {"name", run_stem(specs[i])}});
  return {{"format", kFormat},
          {"version", 1},
          {"campaign", campaign_to_json(config)},
          {"runs_in_campaign", specs.size()},
          {"task", task},
          {"tasks", tasks},
          {"runs", runs}};
}

std::optional<TaskManifest> parse_task_manifest(std::string_view text, const std::string& where,
                                                std::string* error) {
  const json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) {
    *error = where + " is unreadable: not a JSON object";
    return std::nullopt;
  }
  if (j.value("format", json()) != kFormat || j.value("version", json()) != 1) {
    *error = where + " is not a version-1 curio-lab task manifest";
    return std::nullopt;
  }
  constexpr auto kMaxInt = static_cast<unsigned long long>(std::numeric_limits<int>::max());
  const json none;
  const json& runs = j.contains("runs") ? j["runs"] : none;
  if (!j.contains("campaign") || !j["campaign"].is_object() ||
      !whole_in(j.value("runs_in_campaign", none), 0, std::numeric_limits<size_t>::max()) ||
      !whole_in(j.value("task", none), 0, kMaxInt) ||
      !whole_in(j.value("tasks", none), 1, kMaxInt) || !runs.is_array()) {
    *error = where + " is unreadable: \"campaign\" must be an object, \"runs\" an array and "
                     "\"runs_in_campaign\", \"task\", \"tasks\" whole numbers (tasks >= 1)";
    return std::nullopt;
  }
  TaskManifest m;
  m.campaign = j["campaign"];
  m.runs_in_campaign = j["runs_in_campaign"].get<size_t>();
  m.task = j["task"].get<int>();
  m.tasks = j["tasks"].get<int>();
  // Task I of N holds I, I + N, I + 2N, ... below R: checked index by index, so that a damaged
  // R is compared with the runs actually listed instead of being expanded.
  const auto step = static_cast<size_t>(m.tasks);
  const size_t expected =
      m.task >= m.tasks ? 0
      : static_cast<size_t>(m.task) >= m.runs_in_campaign
          ? 0
          : (m.runs_in_campaign - static_cast<size_t>(m.task) - 1) / step + 1;
  bool consistent = m.task < m.tasks && runs.size() == expected;
  for (size_t k = 0; consistent && k < runs.size(); ++k) {
    const json& r = runs[k];
    consistent = r.is_object() && r.contains("index") && r["index"].is_number_unsigned() &&
                 r["index"].get<size_t>() == static_cast<size_t>(m.task) + k * step;
    if (consistent) m.runs.push_back(r["index"].get<size_t>());
  }
  if (!consistent) {
    *error = where + " is inconsistent (its runs are not task " + std::to_string(m.task) +
             " of " + std::to_string(m.tasks) + " of " + std::to_string(m.runs_in_campaign) +
             " runs)";
    return std::nullopt;
  }
  return m;
}

std::optional<TaskManifest> read_task_manifest(const std::string& dir, std::string* error) {
  const std::string path = manifest_path(dir);
  std::ifstream f(path, std::ios::binary);
  if (!f) {
    *error = "no " + path;
    return std::nullopt;
  }
  const std::string text{std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
  return parse_task_manifest(text, path, error);
}

}  // namespace curio::lab
