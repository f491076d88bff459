// The Arm-2-Balls world (SPEC §1): a 7-joint planar arm, a ball it can grasp and a
// distractor on a random walk. Two physics behind one interface: the kinematic
// reference model (the paper's environment, the oracle) and the ODE arm.
#pragma once
#include <cstdint>
#include <memory>
#include <string_view>

#include "firmware/explore/config.hpp"

namespace curio::sim {

enum class Physics { kKinematic, kOde };

// Parses "kinematic" / "ode"; returns false on anything else.
bool parse_physics(std::string_view name, Physics* out);
const char* physics_name(Physics p);

struct WorldParams {
  double grasp_radius = 0.1;      // SPEC §1.1 step 2 (strict <)
  double distractor_noise = 0.1;  // std of the distractor's per-step random walk
};

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

struct SceneState {
  Vec2 hand;
  Vec2 ball;
  Vec2 distractor;
  bool grasped = false;
};

// One world with its own distractor random stream, seeded once at creation and
// advancing across episodes (so the same seed gives the same sequence of episodes).
class World {
 public:
  virtual ~World() = default;

  // Start of an episode: arm at zeros (hand at (1,0)), ball at (0.6,0.6),
  // distractor at (0.7,−0.45), not grasped.
  virtual void reset() = 0;

  // One control period with joint commands a ∈ [−1,1]^7 (SPEC §1.1 steps 1–4).
  virtual void step(const float commands[kJoints]) = 0;

  // One control period with joint angles in rad, each relative to its parent link (what a
  // joint servo is told over the bus): kinematic: absolute angle_j = Σ_{i≤j} angle_i; ODE:
  // each hinge servo's target. Steps 2–4 as in step().
  virtual void step_joint_angles(const double angle_rad[kJoints]) = 0;

  // Angle of joint j relative to its parent link as the joint's encoder reads it (rad).
  virtual double joint_angle_rad(int j) const = 0;

  // reset(), except that the distractor's random stream is rewound to where the last
  // reset() left it: the last episode can be run again identically (a retried episode).
  virtual void replay_episode() = 0;

  // reset() for episode `episode` of the run: the distractor's stream is positioned where
  // `episode` episodes of kStepsPerEpisode steps from the seed leave it, so the episode's
  // randomness is a function of (seed, episode) alone. Equal to reset() after exactly
  // `episode` episodes of 50 steps (as a run has); a replay, or a restarted world, gets the
  // same episode again (curio-sim serve, after a fault or a restart).
  virtual void reset_to_episode(uint64_t episode) = 0;

  virtual const SceneState& state() const = 0;

  // Between episodes: the arm moves back to its start pose (all joints at 0), each joint by at
  // most max_step_rad[j] per control period, before reset_to_episode() or replay_episode()
  // put the scene at its start. Returns the control periods it took. The kinematic model
  // keeps its instant reset (0 periods); the ODE arm drives its hinge servos there, so that a
  // real arm's motion is what the simulation does. The next reset ends in exactly the state it
  // gives without this motion (so every run's results stay as they are).
  virtual int return_to_start(const double max_step_rad[kJoints]) {
    (void)max_step_rad;
    return 0;
  }

  // A motor speed limit of the joints in rad/s (0: none, the default): a joint told to move
  // faster lags behind its target. Only the ODE arm can lag (the kinematic model follows
  // every target at once); the simulated drives then see a following error. For fault
  // injection and tests; no default run sets it.
  virtual void set_joint_speed_limit(double rad_per_s) { (void)rad_per_s; }

  // reset() then the 50 steps of the motor primitive of θ; returns the final state.
  SceneState rollout(const float theta[kThetaDim]);

  // reset() then the 50 steps of the motor primitive of θ as the controller drives the arm
  // over the bus: each command through the one joint-target quantization
  // (firmware/app/joint_target.hpp: π·a → counts → rad) into step_joint_angles(). curio-lab
  // runs this, so in-process and bus runs agree bit for bit. Commands are clipped to
  // [−1, 1] by the primitive, so the quantization cannot fail.
  SceneState rollout_joint_targets(const float theta[kThetaDim]);
};

// The world seed of a run: derived from the run seed so that runs with the same seed see
// the same distractor walk whatever the algorithm (curio-lab and `curio-sim serve --seed`).
uint64_t world_seed_for_run(uint64_t run_seed);

std::unique_ptr<World> make_world(Physics physics, const WorldParams& params, uint64_t seed);

}  // namespace curio::sim
