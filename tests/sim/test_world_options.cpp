// The world options curio-sim rollout and serve share (sim/cli/world_options.hpp): parsed into
// the caller's fields, physics restricted to kinematic/ode, the parameters checked.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "sim/cli/world_options.hpp"

namespace curio::sim {
namespace {

std::string checked(double grasp_radius, double distractor_noise, bool* ok) {
  std::FILE* err = std::tmpfile();
  *ok = check_world_params(grasp_radius, distractor_noise, err);
  std::rewind(err);
  char buffer[256] = {};
  const size_t n = std::fread(buffer, 1, sizeof buffer - 1, err);
  std::fclose(err);
  return std::string(buffer, n);
}

TEST(WorldOptions, ParsedIntoTheCallersFields) {
  CLI::App app;
  std::string physics = "kinematic";
  double radius = 0.1, noise = 0.1;
  add_physics_option(&app, &physics);
  add_world_params_options(&app, &radius, &noise);
  app.parse("--physics ode --grasp-radius 0.25 --distractor-noise 0", false);
  EXPECT_EQ(physics, "ode");
  EXPECT_EQ(radius, 0.25);
  EXPECT_EQ(noise, 0.0);
  EXPECT_THROW(app.parse("--physics bullet", false), CLI::ValidationError);
}

TEST(WorldOptions, ParametersMustBeFiniteAndNonNegative) {
  bool ok = false;
  EXPECT_EQ(checked(0.0, 0.0, &ok), "");
  EXPECT_TRUE(ok);
  EXPECT_EQ(checked(-0.1, 0.1, &ok),
            "curio-sim: --grasp-radius must be a finite number >= 0 (got -0.1)\n");
  EXPECT_FALSE(ok);
  EXPECT_EQ(checked(0.1, -1.0, &ok),
            "curio-sim: --distractor-noise must be a finite number >= 0 (got -1)\n");
  EXPECT_FALSE(ok);
  EXPECT_NE(checked(NAN, 0.1, &ok).find("--grasp-radius"), std::string::npos);
  EXPECT_FALSE(ok);
  EXPECT_NE(checked(0.1, INFINITY, &ok).find("--distractor-noise"), std::string::npos);
  EXPECT_FALSE(ok);
}

}  // namespace
}  // namespace curio::sim
