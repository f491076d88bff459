#include "host_tools/lab/run_record_format.hpp"

#include <nlohmann/json.hpp>

#include "firmware/journal/crc32.hpp"

namespace curio::lab {
using nlohmann::json;

namespace {
constexpr const char* kFormat = "curio-lab run record";
// Version 2: the run's fields are CBOR bytes inside the record, with their CRC-32 beside them.
constexpr int kVersion = 2;

uint32_t crc_of(const std::vector<uint8_t>& bytes) {
  return journal::crc32(bytes.data(), bytes.size());
}
}  // namespace

std::vector<uint8_t> encode_run_record(size_t index, const std::string& name, const RunResult& r) {
  json j;
  j["index"] = index;
  j["name"] = name;
  j["checkpoints"] = r.checkpoints;
  j["ratio"] = r.ratio;
  j["grasps"] = r.grasps;
  std::vector<float> ball;  // x0, y0, x1, y1, ...
  ball.reserve(2 * r.final_ball.size());
  for (const auto& p : r.final_ball) ball.insert(ball.end(), p.begin(), p.end());
  j["final_ball"] = ball;
  j["interest_episodes"] = r.interest_episodes;
  j["interest"] = r.interest;
  j["module_choices"] = r.module_choices;
  j["module_names"] = r.module_names;
  j["module_latents"] = r.module_latents;
  json verdicts = json::array();
  for (const auto& v : r.verdicts)
    verdicts.push_back(
        {v.exploits, v.mean_progress, v.t, v.mean_interest, v.relative_interest, v.controllable});
  j["verdicts"] = verdicts;
  j["seconds"] = r.seconds;
  j["cpu_seconds"] = r.cpu_seconds;
  j["error"] = r.error;
  const std::vector<uint8_t> body = json::to_cbor(j);
  json record;
  record["format"] = kFormat;
  record["version"] = kVersion;
  record["crc32"] = crc_of(body);
  record["body"] = json::binary(body);
  return json::to_cbor(record);
}

std::optional<RunResult> decode_run_record(const std::vector<uint8_t>& bytes, size_t index,
                                           const std::string& name, std::string* error) {
  RunResult r;
  try {
    const json record = json::from_cbor(bytes);
    if (!record.is_object() || !record.contains("format") || record["format"] != kFormat ||
        !record.contains("version") || record["version"] != kVersion) {
      *error = "not a version-" + std::to_string(kVersion) + " run record";
      return std::nullopt;
    }
    const std::vector<uint8_t>& body = record.at("body").get_binary();
    if (!record.at("crc32").is_number_unsigned() ||
        record.at("crc32").get<uint64_t>() != crc_of(body)) {
      *error = "damaged (CRC mismatch)";
      return std::nullopt;
    }
    const json j = json::from_cbor(body);
    if (!j.at("index").is_number_unsigned() || j.at("index").get<size_t>() != index ||
        j.at("name") != name) {
      *error = "holds run " + j.at("index").dump() + " " + j.at("name").dump() + ", not run " +
               std::to_string(index) + " \"" + name + "\"";
      return std::nullopt;
    }
    j.at("checkpoints").get_to(r.checkpoints);
    j.at("ratio").get_to(r.ratio);
    j.at("grasps").get_to(r.grasps);
    const auto ball = j.at("final_ball").get<std::vector<float>>();
    for (size_t i = 0; i + 1 < ball.size(); i += 2) r.final_ball.push_back({ball[i], ball[i + 1]});
    j.at("interest_episodes").get_to(r.interest_episodes);
    j.at("interest").get_to(r.interest);
    j.at("module_choices").get_to(r.module_choices);
    j.at("module_names").get_to(r.module_names);
    j.at("module_latents").get_to(r.module_latents);
    for (const auto& v : j.at("verdicts"))
      r.verdicts.push_back({v.at(0).get<int>(), v.at(1).get<double>(), v.at(2).get<double>(),
                            v.at(3).get<double>(), v.at(4).get<double>(), v.at(5).get<bool>()});
    r.seconds = j.at("seconds").get<double>();
    r.cpu_seconds = j.at("cpu_seconds").get<double>();
    r.error = j.at("error").get<std::string>();
    const bool consistent = r.ratio.size() == r.checkpoints.size() &&
                            r.grasps.size() == r.checkpoints.size() && ball.size() % 2 == 0 &&
                            r.interest.size() == r.interest_episodes.size();
    if (!consistent) {
      *error = "inconsistent (array lengths disagree)";
      return std::nullopt;
    }
  } catch (const json::exception& e) {
    *error = std::string("unreadable: ") + e.what();
    return std::nullopt;
  }
  return r;
}

}  // namespace curio::lab
