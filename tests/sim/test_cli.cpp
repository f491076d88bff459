// The curio-sim binary as a user runs it: good input, each kind of bad input, options.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "firmware/explore/prng.hpp"
#include "sim/world.hpp"

namespace curio::sim {
namespace {

namespace fs = std::filesystem;

struct Result {
  int exit_code = -1;
  std::string out;
  std::string err;
};

std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class CurioSimCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("curio_sim_cli_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  Result run(const std::string& args, const std::string& input = "") {
    std::ofstream(dir_ / "in.txt") << input;
    const std::string command = std::string("'") + CURIO_SIM_BINARY + "' " + args + " < '" +
                                (dir_ / "in.txt").string() + "' > '" + (dir_ / "out.txt").string() +
                                "' 2> '" + (dir_ / "err.txt").string() + "'";
    const int status = std::system(command.c_str());
    Result r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(dir_ / "out.txt");
    r.err = slurp(dir_ / "err.txt");
    return r;
  }

  fs::path dir_;
};

std::string theta_line(const std::vector<float>& theta, const char* sep) {
  std::string s;
  char buf[64];
  for (size_t i = 0; i < theta.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(theta[i]));
    s += (i ? sep : "") + std::string(buf);
  }
  return s + "\n";
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

TEST_F(CurioSimCli, RolloutPrintsFinalStatesOfAPersistentWorld) {
  Prng rng(5);
  std::vector<std::vector<float>> thetas(3, std::vector<float>(kThetaDim, 0.0f));
  for (size_t e = 1; e < thetas.size(); ++e) {
    for (float& v : thetas[e]) v = static_cast<float>(rng.uniform(-1.0, 1.0));
  }
  const std::string input = "# three episodes\n" + theta_line(thetas[0], " ") + "\n" +
                            theta_line(thetas[1], ",") + theta_line(thetas[2], ", ");
  for (const char* physics : {"kinematic", "ode"}) {
    const Result r = run(std::string("rollout --seed 9 --physics ") + physics, input);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    const auto out = lines(r.out);
    ASSERT_EQ(out.size(), 3u);
    if (std::string(physics) == "kinematic") {
      EXPECT_EQ(out[0].substr(0, 42), "0 0.59999999999999998 0.59999999999999998 ");
      EXPECT_EQ(out[0].substr(out[0].size() - 4), " 1 0");
    }
    Physics p{};
    ASSERT_TRUE(parse_physics(physics, &p));
    auto world = make_world(p, {}, 9);
    for (size_t e = 0; e < thetas.size(); ++e) {
      const SceneState s = world->rollout(thetas[e].data());
      char expected[512];
      std::snprintf(expected, sizeof expected, "%d %.17g %.17g %.17g %.17g %.17g %.17g",
                    s.grasped ? 1 : 0, s.ball.x, s.ball.y, s.distractor.x, s.distractor.y, s.hand.x,
                    s.hand.y);
      EXPECT_EQ(out[e], expected) << physics << " episode " << e;
    }
  }
}

TEST_F(CurioSimCli, OptionsChangeTheWorld) {
  const std::string zero = theta_line(std::vector<float>(kThetaDim, 0.0f), " ");
  // Zero noise: the distractor stays at its start. The hand rests at (1, 0), 0.72 from
  // the ball: radius 1 grasps at the first step, so the ball ends at (1, 0).
  const Result r = run("rollout --distractor-noise 0 --grasp-radius 1", zero);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "1 1 0 0.69999999999999996 -0.45000000000000001 1 0\n");
}

TEST_F(CurioSimCli, EachKindOfBadLineExitsTwoWithItsLineNumber) {
  const std::string good = theta_line(std::vector<float>(kThetaDim, 0.1f), " ");
  std::string bad48;
  for (int i = 0; i < 48; ++i) bad48 += "0 ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {bad48 + "\n", "expected 49 numbers, got 48"},
      {bad48 + "zero\n", "is not a number"},
      {bad48 + "nan\n", "is not finite"},
      {bad48 + "inf\n", "is not finite"},
      {bad48 + "1.5\n", "outside [-1, 1]"},
      {bad48 + "-2\n", "outside [-1, 1]"},
  };
  for (const auto& [line, what] : cases) {
    // Line 1 comment, line 2 good, line 3 blank, line 4 bad, line 5 good (never run).
    const Result r = run("rollout", "# c\n" + good + "\n" + line + good);
    EXPECT_EQ(r.exit_code, 2) << line;
    EXPECT_NE(r.err.find("curio-sim: line 4: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
    EXPECT_EQ(lines(r.out).size(), 1u) << "only the good line before it is answered";
  }
}

TEST_F(CurioSimCli, BadOptionsExitTwoWithAMessage) {
  const std::string zero = theta_line(std::vector<float>(kThetaDim, 0.0f), " ");
  for (const std::string args :
       {"rollout --grasp-radius -0.1", "rollout --distractor-noise -1", "rollout --physics bullet",
        "rollout --seed banana", "rollout --grasp-radius nan", "frobnicate", ""}) {
    const Result r = run(args, zero);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.err.find("curio-sim"), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(r.out, "") << args;
  }
  const Result negative = run("rollout --grasp-radius -0.1", zero);
  EXPECT_NE(negative.err.find("--grasp-radius"), std::string::npos) << negative.err;
}

TEST_F(CurioSimCli, HelpExitsZero) {
  for (const std::string args : {"--help", "rollout --help", "render --help"}) {
    const Result r = run(args);
    EXPECT_EQ(r.exit_code, 0) << args;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << args;
  }
}

TEST_F(CurioSimCli, RenderWritesAPng) {
  const fs::path png = dir_ / "scene.png";
  Result r = run("render --ball 0.1 0.2 --distractor -0.3 0.1 --png '" + png.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(png));
  const std::string bytes = slurp(png);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  r = run("render --ball 0.1 0.2 --distractor -0.3 0.1 --scale 4 --png '" + png.string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = run("render --ball 0.1 0.2 --distractor -0.3 0.1 --scale 0 --png '" + png.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  r = run("render --ball 0.1 --distractor -0.3 0.1 --png '" + png.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  r = run("render --ball 0.1 0.2");  // no output file
  EXPECT_EQ(r.exit_code, 2);
}

// A position outside the arena the image shows is refused, no PNG written.
TEST_F(CurioSimCli, RenderRefusesAPositionOutsideTheArena) {
  const fs::path png = dir_ / "outside.png";
  for (const std::string pos : {"--ball 5 5", "--ball 0 -1.2", "--distractor 1.01 0"}) {
    const Result r = run("render " + pos + " --png '" + png.string() + "'");
    EXPECT_EQ(r.exit_code, 2) << pos;
    EXPECT_NE(r.err.find("is outside the arena [-1, 1] x [-1, 1]"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(pos.substr(0, pos.find(' '))), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(png)) << pos;
  }
  const Result edge = run("render --ball 1 -1 --distractor -1 1 --png '" + png.string() + "'");
  EXPECT_EQ(edge.exit_code, 0) << edge.err;  // the corners are still in the arena
}

}  // namespace
}  // namespace curio::sim
