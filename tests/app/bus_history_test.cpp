// bus_counters.json (host_tools/controller/bus_history.hpp), the fault counts of a resumed run's
// earlier processes: read back only when every count is a whole number >= 0, every fault a
// known kind and the kinds add up to the total. A damaged file is refused, never added in
// (a negative count once showed as 18446744073709551611 faults).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "hal/host/loopback_bus.hpp"
#include "host_tools/controller/bus_history.hpp"
#include "tests/app/app_test_util.hpp"

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

// A deleted bus_counters.json beside a journal with episodes cannot erase the run's fault
// history: the resume is refused, naming both files, before the arm moves; with the file back
// it resumes.

namespace curio::app::test {
namespace {

host::BusRunResult run_journaled(const lab::RunSpec& spec, const std::string& dir, bool resume) {
  auto wire = hal::LoopbackBus::create();
  auto arm_end = wire->open();
  auto controller_end = wire->open();
  ArmThread arm(arm_end.get(), serve_options(spec));
  host::BusRunOptions o;
  o.spec = spec;
  o.controller = fast_fault_config();
  o.journal_path = dir + "/journal.bin";
  o.bus_history_path = dir + "/" + host::kBusHistoryFileName;
  o.resume = resume;
  host::BusRunResult r = host::run_over_bus(controller_end.get(), o);
  arm.stop();
  return r;
}

TEST(BusHistory, AResumeWithoutTheCountersFileBesideAJournalIsRefused) {
  const std::string dir = (std::filesystem::temp_directory_path() /
                           ("curio_history_resume_" + std::to_string(::getpid())))
                              .string();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const lab::RunSpec spec = mge_efr_spec(sim::Physics::kKinematic, 0, 10, 10);
  ASSERT_TRUE(run_journaled(spec, dir, false).run.error.empty());
  const std::string counters = dir + "/" + host::kBusHistoryFileName;
  ASSERT_TRUE(std::filesystem::exists(counters));
  const std::string kept = dir + "/kept.json";
  std::filesystem::rename(counters, kept);

  const host::BusRunResult refused = run_journaled(spec, dir, true);
  EXPECT_NE(refused.run.error.find("journal.bin: cannot resume: it holds 20 episodes, but " +
                                   counters + " (the run's fault, replay and process counts) "
                                   "is missing"),
            std::string::npos)
      << refused.run.error;
  EXPECT_TRUE(refused.run.final_ball.empty());
  EXPECT_FALSE(std::filesystem::exists(counters)) << "nothing was changed";

  std::filesystem::rename(kept, counters);
  const host::BusRunResult resumed = run_journaled(spec, dir, true);
  EXPECT_TRUE(resumed.run.error.empty()) << resumed.run.error;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace curio::app::test
