// The host's run journal (host_tools/journal/run_journal.hpp: what curio-controller --resume
// calls) on a real file: a resume under another configuration is refused with a message naming
// the difference, a corrupt record before the tail is refused naming the record, and in both
// cases the file is left byte for byte as it was; a torn tail is dropped, reported, and the
// run continues.
#include "host_tools/journal/run_journal.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "host_tools/experiment/explore_strategies.hpp"
#include "tests/journal/kinematic_run.hpp"

namespace curio::journal::test {
namespace {

namespace fs = std::filesystem;

// No fdatasync per record: these tests are about content, not durability (and stay fast).
constexpr uint32_t kNoSync = 0;

std::vector<uint8_t> file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::vector<uint8_t>& b) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

RunIdentity host_identity(const lab::RunSpec& spec) {
  ExplorerConfig config;
  EXPECT_EQ(lab::make_explorer_config(spec, &config), Status::kOk);
  return host::identity_of(spec, config, /*physics kinematic*/ 0);
}

class RunJournalTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("curio_run_journal_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    path_ = (dir_ / host::kJournalFileName).string();
    // 80 episodes of MGE-EFR seed 5 journaled, then the process "dies".
    std::string error;
    auto j = host::RunJournal::open(path_, &error, kNoSync);
    ASSERT_TRUE(j) << error;
    EXPECT_FALSE(j->has_journal());
    ASSERT_TRUE(j->start(host_identity(spec_), &error)) << error;
    ArmRun run(spec_);
    run.run_until(80, [&](const EpisodeEntry& e) { return j->append(e, &error); });
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Resume with `identity`; the run's explorer is built from `spec`.
  bool resume(const lab::RunSpec& spec, const RunIdentity& identity, std::string* error,
              std::string* notice = nullptr, int* replayed = nullptr, ArmRun** out = nullptr) {
    journal_ = host::RunJournal::open(path_, error, kNoSync);
    EXPECT_TRUE(journal_) << *error;
    run_ = std::make_unique<ArmRun>(spec);
    int n = 0;
    const bool ok = journal_->resume(
        identity, run_->explorer.get(), [&](const EpisodeEntry&, const Explorer&) { ++n; }, error,
        notice);
    if (replayed) *replayed = n;
    if (out) *out = run_.get();
    return ok;
  }

  lab::RunSpec spec_ = spec_of("MGE-EFR", 5);
  fs::path dir_;
  std::string path_;
  std::unique_ptr<host::RunJournal> journal_;
  std::unique_ptr<ArmRun> run_;
};

TEST_F(RunJournalTest, SameRunResumesByReplay) {
  std::string error, notice;
  int replayed = 0;
  ArmRun* run = nullptr;
  ASSERT_TRUE(resume(spec_, host_identity(spec_), &error, &notice, &replayed, &run)) << error;
  EXPECT_EQ(replayed, 80);
  EXPECT_EQ(run->explorer->episode(), 80);
  EXPECT_NE(notice.find("80 episodes journaled"), std::string::npos) << notice;
  // Continue to the end; the result is the uninterrupted run's.
  run->world->reset_to_episode(80);
  run->run_until(1 << 30, [&](const EpisodeEntry& e) { return journal_->append(e, &error); });
  EXPECT_EQ(checksum(*run->explorer), live_checksum(spec_));
}

TEST_F(RunJournalTest, AnotherConfigurationIsRefusedNamingTheDifference) {
  const std::vector<uint8_t> before = file_bytes(path_);
  struct Case {
    const char* what;
    lab::RunSpec spec;
    RunIdentity identity;
    std::string message;
  };
  std::vector<Case> cases;
  {
    lab::RunSpec s = spec_of("MGE-EFR", 6);
    cases.push_back({"seed", s, host_identity(s), "journal is seed 5, this run is seed 6"});
  }
  {
    lab::RunSpec s = spec_of("RGE-EFR", 5);
    cases.push_back({"algorithm", s, host_identity(s),
                     "journal is algorithm MGE-EFR, this run is algorithm RGE-EFR"});
  }
  {
    lab::RunSpec s = spec_;
    s.explorer.sigma = 0.1f;
    cases.push_back({"sigma", s, host_identity(s), "journal is sigma 0.05, this run is sigma 0.1"});
  }
  {
    // A learned goal space with other encoder weights: same settings, another weights hash.
    RunIdentity id = host_identity(spec_);
    id.weights_hash = 0xdeadbeefu;
    cases.push_back({"weights", spec_, id,
                     "journal is encoder weights 00000000, this run is encoder weights deadbeef"});
  }
  {
    lab::RunSpec s = spec_;
    s.explorer.n_episodes = kEpisodes + 100;
    cases.push_back(
        {"episodes", s, host_identity(s), "journal is episodes 250, this run is episodes 350"});
  }
  for (const Case& c : cases) {
    std::string error;
    EXPECT_FALSE(resume(c.spec, c.identity, &error)) << c.what;
    EXPECT_NE(error.find("cannot resume: " + c.message), std::string::npos)
        << c.what << ": " << error;
    EXPECT_NE(error.find("nothing was changed"), std::string::npos) << error;
    EXPECT_EQ(run_->explorer->episode(), 0) << "nothing replayed into the explorer";
    journal_.reset();
    EXPECT_EQ(file_bytes(path_), before) << c.what;
  }
}

TEST_F(RunJournalTest, CorruptRecordBeforeTheTailIsRefusedNamingIt) {
  std::vector<uint8_t> b = file_bytes(path_);
  b[128 + 10 * 64 + 44] ^= 0x01;  // record 10's outcome
  write_bytes(path_, b);
  std::string error;
  EXPECT_FALSE(resume(spec_, host_identity(spec_), &error));
  EXPECT_NE(error.find("record 10 is corrupt (CRC mismatch) and 10 good episodes precede it"),
            std::string::npos)
      << error;
  journal_.reset();
  EXPECT_EQ(file_bytes(path_), b);
}

TEST_F(RunJournalTest, TornTailIsDroppedReportedAndTheRunContinues) {
  std::vector<uint8_t> b = file_bytes(path_);
  ASSERT_EQ(b.size(), 128u + 80u * 64u);
  b.resize(b.size() - 23);  // the last record's write cut short (a kill mid-write)
  write_bytes(path_, b);
  std::string error, notice;
  ArmRun* run = nullptr;
  ASSERT_TRUE(resume(spec_, host_identity(spec_), &error, &notice, nullptr, &run)) << error;
  EXPECT_NE(notice.find("79 episodes journaled; torn record at slot 79"), std::string::npos)
      << notice;
  EXPECT_EQ(run->explorer->episode(), 79);
  run->world->reset_to_episode(79);
  run->run_until(1 << 30, [&](const EpisodeEntry& e) { return journal_->append(e, &error); });
  EXPECT_EQ(checksum(*run->explorer), live_checksum(spec_));
  journal_.reset();
  // Reopened: the whole run, the torn slot acknowledged by the skip record.
  auto j = host::RunJournal::open(path_, &error, kNoSync);
  ASSERT_TRUE(j);
  EXPECT_EQ(j->scan().status, JournalStatus::kOk);
  EXPECT_EQ(j->scan().episodes, static_cast<uint32_t>(kBootstrap + kEpisodes));
  EXPECT_EQ(j->scan().acknowledged_slots, 1u);
  EXPECT_FALSE(j->scan().torn_tail);
}

TEST(RunJournalIdentity, AGoalScaleTheFormatCannotNameIsRefused) {
  const lab::RunSpec spec = spec_of("MGE-EFR", 5);
  ExplorerConfig config;
  ASSERT_EQ(lab::make_explorer_config(spec, &config), Status::kOk);
  config.goal_scale = 2.0f;
  EXPECT_THROW(host::identity_of(spec, config, 0), std::invalid_argument);
}

TEST(RunJournalDescribe, DifferencesAreSpelledOut) {
  RunIdentity a = test_identity(3), b = test_identity(4);
  EXPECT_EQ(host::describe_difference(a, a), "");
  EXPECT_EQ(host::describe_difference(a, b), "journal is seed 3, this run is seed 4");
  b = a;
  b.physics = 1;
  EXPECT_EQ(host::describe_difference(a, b),
            "journal is physics kinematic, this run is physics ODE");
}

TEST(RunJournalDescribe, TheExploreStrategyIsNamedByItsCurioLabName) {
  const lab::RunSpec spec = spec_of("MGE-EFR", 5);
  ExplorerConfig config;
  ASSERT_EQ(lab::make_explorer_config(spec, &config), Status::kOk);
  const RunIdentity plain = host::identity_of(spec, config, 0);
  lab::apply_explore_strategy(*lab::find_explore_strategy("beyond"), &config);
  const RunIdentity beyond = host::identity_of(spec, config, 0);
  EXPECT_EQ(host::describe_difference(beyond, plain),
            "journal is explore strategy beyond, this run is explore strategy spec");
  EXPECT_NE(host::describe(beyond).find("(explore beyond)"), std::string::npos);
  EXPECT_EQ(host::describe(plain).find("explore"), std::string::npos);
  config.frontier_share = 0.25f;
  EXPECT_EQ(host::describe_difference(beyond, host::identity_of(spec, config, 0)),
            "journal is explore strategy beyond, this run is explore strategy frontier share "
            "0.25, σ ladder ×(1,2,2,4)");
}

}  // namespace
}  // namespace curio::journal::test
