// libFuzzer target: the files the host tools read back, on arbitrary bytes and on valid files
// with damage. Oracles beyond "no crash, no UB":
//   - a curio-lab run record (host_tools/lab/run_record_format.hpp) that decodes re-encodes to
//     a record that decodes to the same arrays;
//   - a valid record with any one byte changed never decodes (its CRC, its structure or its
//     identity catches it): a damaged record is never read as a result;
//   - a bus history (bus_counters.json, host_tools/controller/bus_history.hpp) that loads has
//     fault kinds adding up to its total and at least one process; one that does not load
//     leaves the history empty;
//   - a task manifest (host_tools/lab/task_manifest.hpp) that parses lists exactly task I of
//     N's runs, and its campaign block, when it parses, writes back to the same JSON (nothing
//     wrapped, cut or dropped); one that does not parse names its file.
#include <fuzzer/FuzzedDataProvider.h>

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <fstream>
#include <string>
#include <vector>

#include "host_tools/controller/bus_history.hpp"
#include "host_tools/experiment/campaign_json.hpp"
#include "host_tools/lab/run_record_format.hpp"
#include "host_tools/lab/task_manifest.hpp"
#include "tests/fuzz/fuzz_check.hpp"

using namespace curio;

namespace {

const std::string kName = "MGE-EFR_sigma0.05_seed3";

void record_bytes(const std::vector<uint8_t>& bytes) {
  std::string error;
  const auto r = lab::decode_run_record(bytes, 3, kName, &error);
  if (!r) {
    check(!error.empty());
    return;
  }
  const auto again = lab::decode_run_record(lab::encode_run_record(3, kName, *r), 3, kName, &error);
  check(again.has_value());
  check(again->checkpoints == r->checkpoints && again->grasps == r->grasps &&
        again->final_ball.size() == r->final_ball.size() &&
        again->module_names == r->module_names && again->error == r->error);
}

void damaged_record(FuzzedDataProvider& in) {
  lab::RunResult r;
  const int n = in.ConsumeIntegralInRange<int>(0, 8);
  for (int i = 0; i < n; ++i) {
    r.checkpoints.push_back(in.ConsumeIntegral<int>());
    r.ratio.push_back(in.ConsumeFloatingPoint<double>());
    r.grasps.push_back(in.ConsumeIntegral<int>());
    r.final_ball.push_back({in.ConsumeFloatingPoint<float>(), in.ConsumeFloatingPoint<float>()});
  }
  r.module_names.push_back(in.ConsumeRandomLengthString(16));
  r.error = in.ConsumeRandomLengthString(16);
  std::vector<uint8_t> bytes = lab::encode_run_record(3, kName, r);
  std::string error;
  check(lab::decode_run_record(bytes, 3, kName, &error).has_value());
  const size_t at = in.ConsumeIntegralInRange<size_t>(0, bytes.size() - 1);
  const auto flip = in.ConsumeIntegralInRange<uint8_t>(1, 255);
  bytes[at] ^= flip;
  check(!lab::decode_run_record(bytes, 3, kName, &error).has_value());
}

void bus_history(const std::vector<uint8_t>& bytes) {
  static const std::string path = "/tmp/curio_fuzz_bus_history_" + std::to_string(getpid());
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  app::host::BusHistory h;
  std::string error;
  if (app::host::load_bus_history(path, &h, &error)) {
    uint64_t kinds = 0;
    for (const uint64_t f : h.faults) kinds += f;
    check(kinds == h.fault_total);
    check(h.processes >= 1);
  } else {
    check(h.fault_total == 0 && h.processes == 0 && !error.empty());
  }
}

void campaign_block(const nlohmann::json& j) {
  std::string error;
  if (const auto c = lab::campaign_from_json(j, &error)) {
    const auto again = lab::campaign_from_json(lab::campaign_to_json(*c), &error);
    check(again.has_value() && lab::campaign_to_json(*again) == lab::campaign_to_json(*c));
    // Everything campaign_to_json writes came from the block itself.
    const nlohmann::json written = lab::campaign_to_json(*c);
    for (const auto& [key, value] : written.items())
      check(j.contains(key) && value == j[key]);
  } else {
    check(!error.empty());
  }
}

void task_manifest(const std::string& text) {
  std::string error;
  const auto m = lab::parse_task_manifest(text, "manifest.json", &error);
  if (!m) {
    check(error.find("manifest.json") != std::string::npos);
    return;
  }
  check(m->tasks >= 1 && m->task >= 0 && m->task < m->tasks);
  check(m->runs.size() <= text.size());
  for (size_t k = 0; k < m->runs.size(); ++k)
    check(m->runs[k] == static_cast<size_t>(m->task) + k * static_cast<size_t>(m->tasks) &&
          m->runs[k] < m->runs_in_campaign);
  campaign_block(m->campaign);
}

// A manifest curio-lab wrote, with one field replaced by a fuzzed value or one byte changed:
// starts the search from the valid file, where the parser's checks are deepest.
void damaged_manifest(FuzzedDataProvider& in) {
  lab::CampaignConfig c;
  c.seeds = {0, in.ConsumeIntegral<uint64_t>()};
  c.episodes = in.ConsumeIntegralInRange<int>(1, 100000);
  const int tasks = in.ConsumeIntegralInRange<int>(1, 8);
  nlohmann::json j = lab::manifest_json(c, in.ConsumeIntegralInRange<int>(0, tasks - 1), tasks);
  static const char* const kKeys[] = {"runs_in_campaign", "task", "tasks", "runs", "version"};
  static const char* const kCampaignKeys[] = {"seeds", "episodes", "bootstrap", "sigmas",
                                              "window", "physics", "algorithms", "epsilon"};
  nlohmann::json value;
  switch (in.ConsumeIntegralInRange<int>(0, 3)) {
    case 0: value = in.ConsumeIntegral<int64_t>(); break;
    case 1: value = in.ConsumeIntegral<uint64_t>(); break;
    case 2: value = in.ConsumeFloatingPoint<double>(); break;
    default: value = nlohmann::json::array({in.ConsumeIntegral<int64_t>()}); break;
  }
  if (in.ConsumeBool())
    j[kKeys[in.ConsumeIntegralInRange<size_t>(0, std::size(kKeys) - 1)]] = value;
  else
    j["campaign"][kCampaignKeys[in.ConsumeIntegralInRange<size_t>(0, std::size(kCampaignKeys) - 1)]] =
        value;
  std::string text = j.dump();
  if (in.ConsumeBool()) text[in.ConsumeIntegralInRange<size_t>(0, text.size() - 1)] ^=
                        in.ConsumeIntegralInRange<char>(1, 127);
  task_manifest(text);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  switch (in.ConsumeIntegralInRange<int>(0, 5)) {
    case 0:
      record_bytes(in.ConsumeRemainingBytes<uint8_t>());
      break;
    case 1:
      damaged_record(in);
      break;
    case 2:
      bus_history(in.ConsumeRemainingBytes<uint8_t>());
      break;
    case 3:
      task_manifest(in.ConsumeRemainingBytesAsString());
      break;
    case 4:
      damaged_manifest(in);
      break;
    default: {
      const auto j = nlohmann::json::parse(in.ConsumeRemainingBytesAsString(), nullptr, false);
      if (!j.is_discarded() && j.is_object()) campaign_block(j);
      break;
    }
  }
  return 0;
}
