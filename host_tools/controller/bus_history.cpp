#include "host_tools/controller/bus_history.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "host_tools/common/atomic_file.hpp"
#include "host_tools/common/bounded_read.hpp"

namespace curio::app::host {

bool load_bus_history(const std::string& path, BusHistory* h, std::string* error) {
  *h = BusHistory{};
  if (!std::filesystem::exists(std::filesystem::symlink_status(path))) return true;
  std::string text;
  if (!curio::host::read_file_bounded(path, curio::host::kJsonFileLimit, &text, error,
                                      "bus history JSON"))
    return false;
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) {
    *error = path + ": not a bus history (JSON object) file";
    return false;
  }
  // Every count a whole number >= 0 as JSON writes it (nlohmann would wrap -5 to 2^64 - 5 and
  // cut 2.5 to 2), every fault a kind this controller knows, and the kinds adding up to the total.
  std::string why;
  const auto count = [&](const nlohmann::json& in, const std::string& key, uint64_t* out) {
    if (!why.empty()) return;
    if (!in.contains(key)) why = "no \"" + key + "\"";
    else if (!in[key].is_number_unsigned()) why = "\"" + key + "\" is " + in[key].dump() +
                                                   ", not a whole number >= 0";
    else *out = in[key].get<uint64_t>();
  };
  count(j, "processes", &h->processes);
  count(j, "fault_total", &h->fault_total);
  count(j, "replays", &h->replays);
  count(j, "capture_retries", &h->capture_retries);
  count(j, "node_reboots", &h->node_reboots);
  if (why.empty() && !(j.contains("faults") && j["faults"].is_object())) why = "no \"faults\" object";
  uint64_t kinds_total = 0;
  if (why.empty()) {
    for (const auto& [name, value] : j["faults"].items()) {
      size_t kind = 0;
      for (size_t i = 1; i < kFaultKinds; ++i)
        if (name == to_string(static_cast<Fault>(i))) kind = i;
      if (kind == 0) {
        why = "unknown fault \"" + name + "\"";
        break;
      }
      count(j["faults"], name, &h->faults[kind]);
      kinds_total += h->faults[kind];
    }
  }
  if (why.empty() && kinds_total != h->fault_total)
    why = "its faults add up to " + std::to_string(kinds_total) + ", not fault_total " +
          std::to_string(h->fault_total);
  if (why.empty() && h->processes == 0) why = "\"processes\" is 0";
  if (!why.empty()) {
    *h = BusHistory{};
    *error = path + ": not a valid bus history: " + why + "; nothing was changed";
    return false;
  }
  return true;
}

BusHistory combined(const BusHistory& earlier, const ControllerCounters& now) {
  BusHistory h = earlier;
  h.processes += 1;
  for (size_t i = 0; i < kFaultKinds; ++i) h.faults[i] += now.faults[i];
  h.fault_total += now.fault_total;
  h.replays += now.replays;
  h.capture_retries += now.capture_retries;
  h.node_reboots += now.node_reboots;
  return h;
}

bool save_bus_history(const std::string& path, const BusHistory& h, std::string* error) {
  nlohmann::json faults = nlohmann::json::object();
  for (size_t i = 1; i < kFaultKinds; ++i)
    if (h.faults[i] > 0) faults[to_string(static_cast<Fault>(i))] = h.faults[i];
  const nlohmann::json j = {{"processes", h.processes},
                            {"faults", faults},
                            {"fault_total", h.fault_total},
                            {"replays", h.replays},
                            {"capture_retries", h.capture_retries},
                            {"node_reboots", h.node_reboots}};
  return curio::host::write_file_atomically(path, j.dump(2) + "\n", error);
}

namespace {

uint64_t judged(const ControllerCounters& c) {
  return c.fault_total + c.replays + c.capture_retries + c.node_reboots;
}

}  // namespace

bool BusHistoryFile::load_earlier(std::string* error) {
  return path_.empty() || load_bus_history(path_, &earlier_, error);
}

void BusHistoryFile::save(const ControllerCounters& now) {
  saved_ = judged(now);
  if (path_.empty()) return;
  std::string why;
  if (!save_bus_history(path_, combined(earlier_, now), &why) && warnings_)
    std::fprintf(warnings_, "curio-controller: warning: %s\n", why.c_str());
}

void BusHistoryFile::save_if_changed(const ControllerCounters& now) {
  if (judged(now) != saved_) save(now);
}

}  // namespace curio::app::host
