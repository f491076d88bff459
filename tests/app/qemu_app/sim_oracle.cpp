// Host only: the scenario's exploration in-process against sim::KinematicWorld, the way
// curio-lab runs it (World::rollout_joint_targets: the one joint-target quantization into
// step_joint_angles; outcome = float of the final scene), reduced to the same archive
// checksum. Equal checksums show the in-image fake arm is the simulator's kinematic world.
#include <cstdint>

#include "firmware/app/joint_target.hpp"
#include "tests/app/qemu_app/controller_run.hpp"
#include "firmware/explore/motor_primitive.hpp"
#include "sim/kinematic_world.hpp"

namespace {
curio::Explorer g_oracle_explorer;
}

uint32_t sim_oracle_archive_checksum() {
  using namespace curio;
  using namespace curio::test;
  if (g_oracle_explorer.init(scenario_explorer_config()) != Status::kOk) return 0;
  sim::WorldParams params;
  params.grasp_radius = kScenarioGraspRadius;
  params.distractor_noise = kScenarioDistractorNoise;
  // sim::world_seed_for_run (sim/world.cpp; not linked here: it drags in the ODE arm).
  sim::KinematicWorld world(params, KinematicArm2Balls::world_seed_for_run(kScenarioSeed));
  const MotorPrimitive primitive;
  float theta[kThetaDim];
  while (!g_oracle_explorer.done()) {
    if (g_oracle_explorer.propose(theta) != Status::kOk) return 0;
    // World::rollout_joint_targets, step for step.
    world.reset();
    float commands[kJoints];
    double angle_rad[kJoints];
    for (int t = 0; t < kStepsPerEpisode; ++t) {
      primitive.commands(theta, t, commands);
      if (!app::quantized_joint_angles(commands, angle_rad)) return 0;
      world.step_joint_angles(angle_rad);
    }
    const sim::SceneState& s = world.state();
    float outcome[kEfrOutcomeDim];
    outcome[kEfrDistractorX] = static_cast<float>(s.distractor.x);
    outcome[kEfrDistractorY] = static_cast<float>(s.distractor.y);
    outcome[kEfrBallX] = static_cast<float>(s.ball.x);
    outcome[kEfrBallY] = static_cast<float>(s.ball.y);
    if (g_oracle_explorer.observe(outcome) != Status::kOk) return 0;
  }
  Fnv1a h;
  h.add_archive(g_oracle_explorer.archive());
  return h.h;
}
