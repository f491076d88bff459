#include "sim/ode_world.hpp"

#include <ode/ode.h>

#include <algorithm>
#include <cmath>

#include "sim/grasp.hpp"
#include "sim/ode_runtime.hpp"
#include "sim/scene.hpp"

namespace curio::sim {
namespace {

constexpr double kLinkDensityKgPerM = 1.0;
constexpr double kLinkRadiusM = 0.01;
constexpr double kObjectMassKg = 0.05;
constexpr double kObjectRadiusM = 0.05;

// Wraps an angle difference into (−π, π]: the servo takes the short way round.
double wrap_angle(double a) {
  a = std::remainder(a, 2.0 * kPi);
  return a <= -kPi ? a + 2.0 * kPi : a;
}

double link_start_x(int j) {
  double x = 0.0;
  for (int i = 0; i < j; ++i) x += kLinkLengths[i];
  return x;
}

dBodyID make_kinematic_sphere(dWorldID world, const Vec2& at) {
  dBodyID body = dBodyCreate(world);
  dMass mass;
  dMassSetSphereTotal(&mass, kObjectMassKg, kObjectRadiusM);
  dBodySetMass(body, &mass);
  dBodySetKinematic(body);
  dBodySetPosition(body, at.x, at.y, 0.0);
  return body;
}

}  // namespace

OdeWorld::OdeWorld(const WorldParams& params, uint64_t seed)
    : params_(params),
      distractor_(params.distractor_noise, seed),
      episode_start_walk_(distractor_) {
  ensure_ode_ready_for_this_thread();
  world_ = dWorldCreate();
  threading_ = dThreadingAllocateSelfThreadedImplementation();
  dWorldSetStepThreadingImplementation(world_, dThreadingImplementationGetFunctions(threading_),
                                       threading_);
  dWorldSetGravity(world_, 0.0, 0.0, 0.0);
  dWorldSetERP(world_, 1.0);
  dWorldSetCFM(world_, 0.0);

  for (int j = 0; j < kJoints; ++j) {
    links_[j] = dBodyCreate(world_);
    dMass mass;
    dMassSetCapsuleTotal(&mass, kLinkDensityKgPerM * kLinkLengths[j], 1, kLinkRadiusM,
                         kLinkLengths[j]);
    dBodySetMass(links_[j], &mass);
    // Large rotations per period: integrate orientation exactly, not to first order.
    dBodySetFiniteRotationMode(links_[j], 1);
    dBodySetGyroscopicMode(links_[j], 0);
  }
  ball_ = make_kinematic_sphere(world_, kBallStart);
  distractor_body_ = make_kinematic_sphere(world_, kDistractorStart);
  reset();  // places the links before the joints record their zero angle

  for (int j = 0; j < kJoints; ++j) {
    hinges_[j] = dJointCreateHinge(world_, nullptr);
    dJointAttach(hinges_[j], links_[j], j == 0 ? nullptr : links_[j - 1]);
    dJointSetHingeAnchor(hinges_[j], link_start_x(j), 0.0, 0.0);
    dJointSetHingeAxis(hinges_[j], 0.0, 0.0, 1.0);
    dJointSetHingeParam(hinges_[j], dParamFMax, dInfinity);
    dJointSetHingeParam(hinges_[j], dParamVel, 0.0);
  }
}

OdeWorld::~OdeWorld() {
  ensure_ode_ready_for_this_thread();
  dWorldDestroy(world_);  // also destroys its bodies and joints
  dThreadingFreeImplementation(threading_);
}

void OdeWorld::reset() {
  distractor_.reset();
  episode_start_walk_ = distractor_;
  start_episode();
}

void OdeWorld::reset_to_episode(uint64_t episode) {
  distractor_.reset_to_episode(episode);
  episode_start_walk_ = distractor_;
  start_episode();
}

void OdeWorld::replay_episode() {
  distractor_ = episode_start_walk_;
  start_episode();
}

void OdeWorld::start_episode() {
  ensure_ode_ready_for_this_thread();
  for (int j = 0; j < kJoints; ++j) {
    // Each link lies along the world x axis at rest (mass set up along body x).
    dBodySetPosition(links_[j], link_start_x(j) + 0.5 * kLinkLengths[j], 0.0, 0.0);
    const dQuaternion identity = {1.0, 0.0, 0.0, 0.0};
    dBodySetQuaternion(links_[j], identity);
    dBodySetLinearVel(links_[j], 0.0, 0.0, 0.0);
    dBodySetAngularVel(links_[j], 0.0, 0.0, 0.0);
  }
  dBodySetPosition(ball_, kBallStart.x, kBallStart.y, 0.0);
  dBodySetPosition(distractor_body_, kDistractorStart.x, kDistractorStart.y, 0.0);
  scene_.hand = hand_tip();
  scene_.ball = kBallStart;
  scene_.distractor = distractor_.position();
  scene_.grasped = false;
}

double OdeWorld::joint_angle_rad(int j) const {
  return dJointGetHingeAngle(hinges_[j]);
}

Vec2 OdeWorld::hand_tip() const {
  dVector3 tip;
  dBodyGetRelPointPos(links_[kJoints - 1], 0.5 * kLinkLengths[kJoints - 1], 0.0, 0.0, tip);
  return {tip[0], tip[1]};
}

void OdeWorld::step(const float commands[kJoints]) {
  double target_rad[kJoints];
  for (int j = 0; j < kJoints; ++j) target_rad[j] = kPi * static_cast<double>(commands[j]);
  servo_step(target_rad);
}

void OdeWorld::step_joint_angles(const double angle_rad[kJoints]) {
  servo_step(angle_rad);
}

void OdeWorld::move_servos(const double target_rad[kJoints]) {
  ensure_ode_ready_for_this_thread();
  // Motion: each servo's velocity motor runs at the speed that reaches its target in
  // one period (or, with a speed limit, at most that speed: the joint lags). The joint
  // angles land on their targets, but a large rotation integrated to first order leaves
  // the links' positions off their hinges.
  constexpr double dt = kControlPeriodS;
  for (int j = 0; j < kJoints; ++j) {
    const double error = wrap_angle(target_rad[j] - dJointGetHingeAngle(hinges_[j]));
    double velocity = error / dt;
    if (speed_limit_rad_s_ > 0)
      velocity = std::clamp(velocity, -speed_limit_rad_s_, speed_limit_rad_s_);
    dJointSetHingeParam(hinges_[j], dParamVel, velocity);
  }
  dWorldStep(world_, dt);
  // Settle: servos hold (zero relative velocity) while the joints' error correction
  // (ERP 1) closes the hinge gaps. With no rotation left, this step is a pure
  // translation, which the integrator performs exactly.
  if (kSettleStep) {
    for (int j = 0; j < kJoints; ++j) dJointSetHingeParam(hinges_[j], dParamVel, 0.0);
    dWorldStep(world_, dt);
  }
}

void OdeWorld::servo_step(const double target_rad[kJoints]) {
  move_servos(target_rad);
  scene_.hand = hand_tip();
  apply_grasp_rule(params_.grasp_radius, &scene_);
  dBodySetPosition(ball_, scene_.ball.x, scene_.ball.y, 0.0);
  distractor_.step();
  scene_.distractor = distractor_.position();
  dBodySetPosition(distractor_body_, scene_.distractor.x, scene_.distractor.y, 0.0);
}

int OdeWorld::return_to_start(const double max_step_rad[kJoints]) {
  // Each hinge toward 0 by at most its step per period, the ball carried if grasped; the
  // distractor is not stepped (the next reset positions it). Bounded: a step of 1e-6 rad
  // would need π·10^6 periods; the drives' steps are far larger.
  constexpr int kMaxPeriods = 100'000;
  constexpr double kAtRestRad = 1e-9;
  int periods = 0;
  for (; periods < kMaxPeriods; ++periods) {
    double target[kJoints];
    bool at_start = true;
    for (int j = 0; j < kJoints; ++j) {
      const double a = dJointGetHingeAngle(hinges_[j]);
      if (std::fabs(a) > kAtRestRad) at_start = false;
      const double step = std::clamp(-a, -max_step_rad[j], max_step_rad[j]);
      target[j] = a + step;
    }
    if (at_start) break;
    move_servos(target);
    scene_.hand = hand_tip();
    if (scene_.grasped) {
      scene_.ball = scene_.hand;
      dBodySetPosition(ball_, scene_.ball.x, scene_.ball.y, 0.0);
    }
  }
  return periods;
}

}  // namespace curio::sim
