// The output folder every Curio program writes into (host_tools/common/output_folder.hpp):
// created if absent, refused when it cannot be written, and one writer at a time, the second
// told who the first is.
#include "host_tools/common/output_folder.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using curio::host::claim_output_folder;
using curio::host::OutputAccess;

namespace {

struct OutputFolderTest : ::testing::Test {
  void SetUp() override {
    root = fs::temp_directory_path() / ("curio_output_folder_" + std::to_string(::getpid()));
    fs::remove_all(root);
    fs::create_directories(root);
  }
  void TearDown() override { fs::remove_all(root); }
  fs::path root;
};

TEST_F(OutputFolderTest, CreatesAMissingFolderAndLeavesNothingInIt) {
  const std::string dir = (root / "a" / "b").string();
  std::string error;
  auto claim = claim_output_folder(dir, OutputAccess::kExclusive, &error);
  ASSERT_NE(claim, nullptr) << error;
  EXPECT_TRUE(fs::is_directory(dir));
  EXPECT_TRUE(fs::is_empty(dir));  // the claim and the write probe leave no file
}

TEST_F(OutputFolderTest, ASecondWriterIsRefusedNamingTheFirst) {
  const std::string dir = root.string();
  std::string error;
  auto first = claim_output_folder(dir, OutputAccess::kExclusive, &error);
  ASSERT_NE(first, nullptr) << error;
  auto second = claim_output_folder(dir, OutputAccess::kExclusive, &error);
  EXPECT_EQ(second, nullptr);
  EXPECT_NE(error.find(dir + " is in use by "), std::string::npos) << error;
  EXPECT_NE(error.find("(PID " + std::to_string(::getpid()) + ", started "), std::string::npos)
      << error;
  EXPECT_NE(error.find("use another --out"), std::string::npos) << error;
  first.reset();  // released: the folder can be claimed again
  EXPECT_NE(claim_output_folder(dir, OutputAccess::kExclusive, &error), nullptr) << error;
}

TEST_F(OutputFolderTest, SharedWritersCoexistAndExcludeAWholeRunsWriter) {
  const std::string dir = root.string();
  std::string error;
  auto task0 = claim_output_folder(dir, OutputAccess::kShared, &error);
  auto task1 = claim_output_folder(dir, OutputAccess::kShared, &error);
  ASSERT_NE(task0, nullptr) << error;
  ASSERT_NE(task1, nullptr) << error;
  EXPECT_EQ(claim_output_folder(dir, OutputAccess::kExclusive, &error), nullptr);
  EXPECT_NE(error.find("is in use by"), std::string::npos) << error;
}

TEST_F(OutputFolderTest, TheHolderInAnotherProcessIsNamedByItsPid) {
  const std::string dir = root.string();
  int ready[2], done[2];
  ASSERT_EQ(::pipe(ready), 0);
  ASSERT_EQ(::pipe(done), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::string e;
    auto claim = claim_output_folder(dir, OutputAccess::kExclusive, &e);
    const char c = claim ? 'y' : 'n';
    (void)!::write(ready[1], &c, 1);
    char x;
    (void)!::read(done[0], &x, 1);  // hold the claim until the parent has looked
    _exit(0);
  }
  char c = 0;
  ASSERT_EQ(::read(ready[0], &c, 1), 1);
  ASSERT_EQ(c, 'y');
  std::string error;
  EXPECT_EQ(claim_output_folder(dir, OutputAccess::kExclusive, &error), nullptr);
  EXPECT_NE(error.find("(PID " + std::to_string(child)), std::string::npos) << error;
  (void)!::write(done[1], "x", 1);
  int status = 0;
  ::waitpid(child, &status, 0);
  // The holder's exit released it, with nothing to clean up.
  EXPECT_NE(claim_output_folder(dir, OutputAccess::kExclusive, &error), nullptr) << error;
}

TEST_F(OutputFolderTest, AFileWhereTheFolderShouldBeIsRefused) {
  const fs::path file = root / "results";
  std::ofstream(file) << "not a folder\n";
  std::string error;
  EXPECT_EQ(claim_output_folder(file.string(), OutputAccess::kExclusive, &error), nullptr);
  EXPECT_NE(error.find("cannot create the folder " + file.string()), std::string::npos) << error;
  std::ifstream in(file);
  std::string text;
  std::getline(in, text);
  EXPECT_EQ(text, "not a folder");  // untouched
}

TEST_F(OutputFolderTest, AFolderThatCannotBeWrittenIsRefusedBeforeAnyWork) {
  // /proc exists and is a folder, but no file can be created in it (not even by root).
  std::string error;
  EXPECT_EQ(claim_output_folder("/proc", OutputAccess::kExclusive, &error), nullptr);
  EXPECT_NE(error.find("cannot write into /proc: "), std::string::npos) << error;
}

TEST_F(OutputFolderTest, AnEmptyPathIsRefused) {
  std::string error;
  EXPECT_EQ(claim_output_folder("", OutputAccess::kExclusive, &error), nullptr);
  EXPECT_NE(error.find("empty"), std::string::npos) << error;
}

TEST(DescribeProcess, NamesAProgramByPidAndStartTime) {
  const std::string me = curio::host::describe_process(::getpid());
  EXPECT_NE(me.find("(PID " + std::to_string(::getpid()) + ", started 20"), std::string::npos)
      << me;
  EXPECT_NE(me.find(" UTC)"), std::string::npos) << me;
  EXPECT_EQ(curio::host::describe_process(-1), "another process");
}

}  // namespace
