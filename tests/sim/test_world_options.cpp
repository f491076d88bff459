// The world options curio-sim rollout and serve share (host_tools/cli/world_options.hpp): parsed
// into the caller's fields, physics restricted to kinematic/ode, the parameters and seed checked
// when parsed.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "host_tools/cli/world_options.hpp"

namespace curio::sim {
namespace {

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
  CLI::App app;
  std::string physics = "kinematic";
  double radius = 0.1, noise = 0.1;
  uint64_t seed = 0;
  add_physics_option(&app, &physics);
  add_world_params_options(&app, &radius, &noise);
  add_seed_option(&app, &seed, "seed");
  EXPECT_NO_THROW(app.parse("--grasp-radius 0 --distractor-noise 0 --seed 7", false));
  EXPECT_EQ(seed, 7u);
  for (const std::string bad : {"--grasp-radius -0.1", "--distractor-noise -1",
                                "--grasp-radius nan", "--distractor-noise inf", "--seed -1",
                                "--seed x"}) {
    try {
      app.parse(bad, false);
      ADD_FAILURE() << bad << " was taken";
    } catch (const CLI::ValidationError& e) {
      EXPECT_NE(std::string(e.what()).find(bad.substr(0, bad.find(' '))), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace curio::sim
