// No write follows a link or a special file, and no reader grows without bound: the host's
// result files (host_tools/common/atomic_file.hpp), bounded reads of input files
// (host_tools/common/bounded_read.hpp) and the journal's storage (hal/host/posix_file_storage.hpp)
// refuse a symbolic link, FIFO, device or directory where a file is expected, naming it.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "hal/host/posix_file_storage.hpp"
#include "host_tools/common/atomic_file.hpp"
#include "host_tools/common/bounded_read.hpp"
#include "host_tools/common/gnuplot.hpp"

namespace curio::host {
namespace {

namespace fs = std::filesystem;

struct Folder {
  fs::path dir = fs::temp_directory_path() / ("curio_special_" + std::to_string(::getpid()));
  Folder() {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~Folder() { fs::remove_all(dir); }
  std::string operator/(const char* name) const { return (dir / name).string(); }
};

std::string contents(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(BoundedRead, ReadsARegularFileWithinItsLimit) {
  Folder f;
  std::string bytes, error;
  ASSERT_TRUE(write_file_atomically(f / "a.json", "{\"x\": 1}\n", &error)) << error;
  ASSERT_TRUE(read_file_bounded(f / "a.json", 64, &bytes, &error)) << error;
  EXPECT_EQ(bytes, "{\"x\": 1}\n");
}

TEST(BoundedRead, RefusesAFilePastItsLimitNamingIt) {
  Folder f;
  std::string error;
  ASSERT_TRUE(write_file_atomically(f / "big", std::string(3 << 20, 'x'), &error));
  std::string bytes;
  EXPECT_FALSE(read_file_bounded(f / "big", 1 << 20, &bytes, &error, "meta JSON"));
  EXPECT_TRUE(has(error, f / "big")) << error;
  EXPECT_TRUE(has(error, "3.0 MiB, more than the 1.0 MiB a meta JSON may have")) << error;
  EXPECT_TRUE(bytes.empty());
}

TEST(BoundedRead, RefusesDevZeroAFifoAndADirectory) {
  Folder f;
  ASSERT_EQ(::mkfifo((f / "fifo").c_str(), 0600), 0);
  std::string bytes, error;
  EXPECT_FALSE(read_file_bounded("/dev/zero", kModelFileLimit, &bytes, &error, "float model"));
  EXPECT_EQ(error, "/dev/zero: a character device, not a regular file (a float model was expected)");
  EXPECT_FALSE(read_file_bounded(f / "fifo", kJsonFileLimit, &bytes, &error));  // no hang
  EXPECT_TRUE(has(error, "a FIFO, not a regular file")) << error;
  EXPECT_FALSE(read_file_bounded(f.dir.string(), kJsonFileLimit, &bytes, &error));
  EXPECT_TRUE(has(error, "a directory")) << error;
  EXPECT_FALSE(read_file_bounded(f / "absent", kJsonFileLimit, &bytes, &error));
  EXPECT_TRUE(has(error, "No such file or directory")) << error;
}

TEST(AtomicFile, RefusesToReplaceALinkAFifoOrADirectoryAndLeavesTheTargetAlone) {
  Folder f;
  std::string error;
  ASSERT_TRUE(write_file_atomically(f / "target", "precious\n", &error));
  fs::create_symlink(f / "target", f / "summary.json");
  EXPECT_FALSE(write_file_atomically(f / "summary.json", "new\n", &error));
  EXPECT_TRUE(has(error, "summary.json: it is a symbolic link, not a regular file; refusing"))
      << error;
  EXPECT_EQ(contents(f / "target"), "precious\n");
  EXPECT_TRUE(fs::is_symlink(f / "summary.json"));

  ASSERT_EQ(::mkfifo((f / "fifo").c_str(), 0600), 0);
  EXPECT_FALSE(write_file_atomically(f / "fifo", "x", &error));
  EXPECT_TRUE(has(error, "it is a FIFO")) << error;
  fs::create_directory(f / "dir");
  EXPECT_FALSE(write_file_atomically(f / "dir", "x", &error));
  EXPECT_TRUE(has(error, "it is a directory")) << error;

  // A file another program wrote (commit_temp) is refused the same way.
  const std::string tmp = temp_path_for(f / "summary.json");
  ASSERT_TRUE(write_file_atomically(tmp, "plot", &error));
  EXPECT_FALSE(commit_temp(tmp, f / "summary.json", &error));
  EXPECT_TRUE(has(error, "symbolic link")) << error;
  EXPECT_FALSE(fs::exists(tmp));
  EXPECT_EQ(contents(f / "target"), "precious\n");
}

TEST(JournalStorage, RefusesALinkAFifoADeviceAndADirectory) {
  Folder f;
  std::string error;
  ASSERT_TRUE(write_file_atomically(f / "target", "precious\n", &error));
  fs::create_symlink(f / "target", f / "journal.bin");
  EXPECT_EQ(hal::PosixFileStorage::open(f / "journal.bin", &error), nullptr);
  EXPECT_TRUE(has(error, "journal.bin: it is a symbolic link; refusing to follow it")) << error;
  EXPECT_EQ(contents(f / "target"), "precious\n");

  ASSERT_EQ(::mkfifo((f / "fifo.bin").c_str(), 0600), 0);
  EXPECT_EQ(hal::PosixFileStorage::open(f / "fifo.bin", &error), nullptr);  // no hang
  EXPECT_TRUE(has(error, "fifo.bin: it is a FIFO, not a regular file")) << error;
  EXPECT_EQ(hal::PosixFileStorage::open("/dev/zero", &error), nullptr);
  EXPECT_EQ(error, "cannot open /dev/zero: it is a character device, not a regular file");
  EXPECT_EQ(hal::PosixFileStorage::open(f.dir.string(), &error), nullptr);
  EXPECT_TRUE(has(error, "it is a directory")) << error;
  auto ok = hal::PosixFileStorage::open(f / "real.bin", &error);
  EXPECT_NE(ok, nullptr) << error;
}

// Plots in a folder whose name has an apostrophe, a space and non-ASCII letters (--out "bob's
// runs" once made every plot fail: the shell took gnuplot's quoting).
TEST(Gnuplot, PlotsIntoAFolderWithAnApostropheASpaceAndNonAsciiLetters) {
  Folder f;
  const fs::path dir = f.dir / "bob's runs — Zürich";
  fs::create_directories(dir);
  const std::string png = (dir / "ratio.png").string();
  const std::string data = (dir / "ratio.dat").string();
  std::string error;
  ASSERT_TRUE(write_file_atomically(data, "0 0\n1 1\n", &error)) << error;
  const std::string script = "set terminal pngcairo size 200,100\nset output " +
                             gnuplot_quote(png) + "\nplot " + gnuplot_quote(data) +
                             " using 1:2 with lines\n";
  bool not_installed = false;
  const bool ok = run_gnuplot((dir / "ratio.gp").string(), script, &error, &not_installed);
  if (not_installed) GTEST_SKIP() << "gnuplot is not installed";
  ASSERT_TRUE(ok) << error;
  EXPECT_GT(fs::file_size(png), 100u);
}

}  // namespace
}  // namespace curio::host
