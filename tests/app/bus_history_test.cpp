// bus_counters.json (host_tools/controller/bus_history.hpp), the fault counts of a resumed run's
// earlier processes: read back only when every count is a whole number >= 0, every fault a
// known kind and the kinds add up to the total. A damaged file is refused, never added in
// (a negative count once showed as 18446744073709551611 faults).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "host_tools/controller/bus_history.hpp"

namespace curio::app::host {
namespace {
namespace fs = std::filesystem;

const fs::path kFile = fs::temp_directory_path() / "curio_bus_history_test.json";

bool load_text(const std::string& text, BusHistory* h, std::string* error) {
  std::ofstream(kFile) << text;
  return load_bus_history(kFile.string(), h, error);
}

TEST(BusHistory, RoundTripsWhatItSaves) {
  BusHistory h;
  h.processes = 2;
  h.faults[static_cast<size_t>(Fault::kFeedbackTimeout)] = 3;
  h.faults[static_cast<size_t>(Fault::kHeartbeatLost)] = 1;
  h.fault_total = 4;
  h.replays = 4;
  h.node_reboots = 8;
  std::string error;
  ASSERT_TRUE(save_bus_history(kFile.string(), h, &error)) << error;
  BusHistory back;
  ASSERT_TRUE(load_bus_history(kFile.string(), &back, &error)) << error;
  EXPECT_EQ(back.fault_total, 4u);
  EXPECT_EQ(back.faults[static_cast<size_t>(Fault::kFeedbackTimeout)], 3u);
  EXPECT_EQ(back.node_reboots, 8u);
  fs::remove(kFile);
}

TEST(BusHistory, ADamagedFileIsRefusedNamingWhatIsWrong) {
  const std::string ok_faults = R"("faults": {"feedback_timeout": 2}, "fault_total": 2)";
  const std::string rest = R"("replays": 0, "capture_retries": 0, "node_reboots": 0)";
  const struct {
    std::string text, says;
  } cases[] = {
      {"{\"processes\": 1, " + ok_faults + ", \"replays\": -5, \"capture_retries\": 0, "
       "\"node_reboots\": 0}", "\"replays\" is -5"},
      {"{\"processes\": 1, " + ok_faults + ", \"replays\": 2.5, \"capture_retries\": 0, "
       "\"node_reboots\": 0}", "\"replays\" is 2.5"},
      {"{\"processes\": 1, \"faults\": {\"feedback_timeout\": -1}, \"fault_total\": 2, " + rest + "}",
       "\"feedback_timeout\" is -1"},
      {"{\"processes\": 1, \"faults\": {\"gremlins\": 2}, \"fault_total\": 2, " + rest + "}",
       "unknown fault \"gremlins\""},
      {"{\"processes\": 1, \"faults\": {\"feedback_timeout\": 1}, \"fault_total\": 2, " + rest +
       "}", "add up to 1, not fault_total 2"},
      {"{\"processes\": 1, " + ok_faults + ", \"replays\": 0, \"node_reboots\": 0}",
       "no \"capture_retries\""},
      {"{\"processes\": 0, " + ok_faults + ", " + rest + "}", "\"processes\" is 0"},
      {"{\"processes\": \"1\", " + ok_faults + ", " + rest + "}", "\"processes\" is \"1\""},
      {"[1, 2]", "not a bus history"},
      {"{\"processes\": 1, ", "not a bus history"},
  };
  for (const auto& c : cases) {
    BusHistory h;
    h.fault_total = 99;
    std::string error;
    EXPECT_FALSE(load_text(c.text, &h, &error)) << c.text;
    EXPECT_NE(error.find(c.says), std::string::npos) << c.text << " -> " << error;
    EXPECT_EQ(h.fault_total, 0u) << "a refused file must leave nothing behind";
  }
  fs::remove(kFile);
}

}  // namespace
}  // namespace curio::app::host
