#include "host_tools/controller/bus_history.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "host_tools/common/atomic_file.hpp"

namespace curio::app::host {

bool load_bus_history(const std::string& path, BusHistory* h, std::string* error) {
  *h = BusHistory{};
  if (!std::filesystem::exists(path)) return true;
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const nlohmann::json j = nlohmann::json::parse(text.str(), nullptr, /*allow_exceptions=*/false);
  if (!in || j.is_discarded() || !j.is_object()) {
    *error = path + ": not a bus history (JSON object) file";
    return false;
  }
  try {
    h->processes = j.at("processes").get<uint64_t>();
    h->fault_total = j.at("fault_total").get<uint64_t>();
    h->replays = j.at("replays").get<uint64_t>();
    h->capture_retries = j.at("capture_retries").get<uint64_t>();
    h->node_reboots = j.at("node_reboots").get<uint64_t>();
    for (size_t i = 1; i < kFaultKinds; ++i) {
      const char* name = to_string(static_cast<Fault>(i));
      if (j.at("faults").contains(name)) h->faults[i] = j["faults"][name].get<uint64_t>();
    }
  } catch (const nlohmann::json::exception& e) {
    *error = path + ": " + e.what();
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
