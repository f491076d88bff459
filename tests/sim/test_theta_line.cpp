// Parsing of `curio-sim rollout` input lines.
#include <gtest/gtest.h>

#include <string>

#include "sim/cli/theta_line.hpp"

namespace curio::sim {
namespace {

std::string repeat(const std::string& value, int n, const std::string& sep) {
  std::string s;
  for (int i = 0; i < n; ++i) {
    if (i) s.append(sep);
    s.append(value);
  }
  return s;
}

TEST(ThetaLine, AcceptsSpacesCommasAndBoth) {
  float theta[kThetaDim];
  std::string error;
  for (const std::string sep : {" ", ",", ", ", "\t", " , "}) {
    ASSERT_EQ(parse_theta_line(repeat("-0.25", kThetaDim, sep), theta, &error),
              ThetaLineStatus::kTheta)
        << "separator '" << sep << "': " << error;
    EXPECT_EQ(theta[0], -0.25f);
    EXPECT_EQ(theta[48], -0.25f);
  }
  ASSERT_EQ(parse_theta_line("  " + repeat("+1", kThetaDim, " ") + " \r", theta, &error),
            ThetaLineStatus::kTheta);
  EXPECT_EQ(theta[10], 1.0f);
}

TEST(ThetaLine, SkipsBlankAndCommentLines) {
  float theta[kThetaDim];
  std::string error;
  EXPECT_EQ(parse_theta_line("", theta, &error), ThetaLineStatus::kSkip);
  EXPECT_EQ(parse_theta_line("   \t", theta, &error), ThetaLineStatus::kSkip);
  EXPECT_EQ(parse_theta_line("# header", theta, &error), ThetaLineStatus::kSkip);
  EXPECT_EQ(parse_theta_line("  # indented", theta, &error), ThetaLineStatus::kSkip);
}

TEST(ThetaLine, RejectsWhatIsWrongAndSaysWhat) {
  float theta[kThetaDim];
  std::string error;
  const auto rejects = [&](const std::string& line, const std::string& expected) {
    error.clear();
    EXPECT_EQ(parse_theta_line(line, theta, &error), ThetaLineStatus::kError) << line;
    EXPECT_NE(error.find(expected), std::string::npos) << "got: " << error;
  };
  rejects(repeat("0", 48, " "), "expected 49 numbers, got 48");
  rejects(repeat("0", 50, " "), "got 50");
  rejects(repeat("0", 48, " ") + " abc", "value 49 ('abc') is not a number");
  rejects(repeat("0", 48, " ") + " 0.5x", "not a number");
  rejects("nan " + repeat("0", 48, " "), "value 1 ('nan') is not finite");
  rejects(repeat("0", 48, " ") + " -inf", "not finite");
  rejects(repeat("0", 48, " ") + " 1.5", "value 49 (1.5) is outside [-1, 1]");
  rejects(repeat("0", 48, " ") + " -1.0001", "outside [-1, 1]");
  rejects(repeat("0", 48, ",") + ",,0", "empty value");
  rejects(std::string(",").append(repeat("0", 49, ",")), "empty value");
  rejects(repeat("0", 49, ",") + ",", "trailing comma");
}

// A 10 MB token is quoted by its first 40 bytes and its size, not whole.
TEST(ThetaLine, QuotesAHugeBadTokenShort) {
  float theta[kThetaDim];
  std::string error;
  const std::string huge(10'000'000, 'x');
  EXPECT_EQ(parse_theta_line(huge, theta, &error), ThetaLineStatus::kError);
  EXPECT_EQ(error, "value 1 ('" + std::string(40, 'x') + "… (10000000 bytes)') is not a number");
  const std::string big_number = "0." + std::string(100, '9') + "1";  // 1.0000…: outside
  EXPECT_EQ(parse_theta_line(repeat("0", 48, " ") + " 1" + big_number.substr(1), theta, &error),
            ThetaLineStatus::kError);
  EXPECT_LT(error.size(), 120u) << error;
  EXPECT_NE(error.find("(103 bytes)) is outside [-1, 1]"), std::string::npos) << error;
  // A multi-byte character is not cut in half.
  const std::string greek = std::string(39, 'a') + "σσσσ";
  EXPECT_EQ(parse_theta_line(greek, theta, &error), ThetaLineStatus::kError);
  EXPECT_NE(error.find("('" + std::string(39, 'a') + "… (47 bytes)')"), std::string::npos) << error;
}

// Control characters in a bad token are quoted as \xNN, never written raw to the terminal.
TEST(ThetaLine, NeverEchoesControlCharacters) {
  float theta[kThetaDim];
  std::string error;
  EXPECT_EQ(parse_theta_line("\x1b[2J\x07oops\x7f", theta, &error), ThetaLineStatus::kError);
  EXPECT_EQ(error, "value 1 ('\\x1b[2J\\x07oops\\x7f') is not a number");
  for (const char c : error) EXPECT_TRUE(static_cast<unsigned char>(c) >= 0x20 && c != 0x7f);
}

}  // namespace
}  // namespace curio::sim
