#include "host_tools/controller/arm_bring_up.hpp"

#include <cstdio>
#include <cstdlib>

#include "firmware/protocol/arm_objects.hpp"
#include "host_tools/controller/fault_text.hpp"
#include "host_tools/journal/run_identity.hpp"
#include "sim/world_identity.hpp"

namespace curio::app::host {


namespace {

namespace od = protocol::od;
using sim::bits_double;

// The shortest text that reads back as the same double: "0.1", not "0.10000000000000001".
std::string number(double v) {
  char s[32];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(s, sizeof s, "%.*g", digits, v);
    if (std::strtod(s, nullptr) == v) break;
  }
  return s;
}

std::string hex(uint32_t v) {
  char b[12];
  std::snprintf(b, sizeof b, "%08x", static_cast<unsigned>(v));
  return b;
}

}  // namespace

bool read_arm_world(Controller& controller, protocol::WorldIdentity* arm, bool* damaged) {
  uint32_t words[protocol::kWorldIdentityWords] = {};
  for (uint8_t sub = 1; sub <= protocol::kWorldIdentityWords; ++sub)
    if (!controller.read_camera_object(od::kWorldIdentity, sub, &words[sub - 1])) return false;
  uint32_t fields[protocol::kWorldIdentityWords - 1] = {};
  for (int i = 0; i + 1 < protocol::kWorldIdentityWords; ++i) fields[i] = words[i];
  *arm = protocol::world_identity_from_words(fields, controller.query_physics());
  if (damaged) *damaged = protocol::world_hash(*arm) != words[protocol::kWorldIdentityWords - 1];
  return true;
}

std::string world_mismatch(Controller& controller, const lab::RunSpec& spec,
                           protocol::WorldIdentity* arm_out, bool* published) {
  protocol::WorldIdentity arm;
  bool damaged = false;
  const bool has = read_arm_world(controller, &arm, &damaged);
  if (published) *published = has;
  if (!has) return "";
  if (arm_out) *arm_out = arm;
  if (damaged) return "the arm's world identity (camera 0x2003) does not match its own hash";
  const protocol::WorldIdentity asked = journal::host::asked_world(spec, arm.physics);
  // Both programs spell the option the same: either side can be changed to match.
  const auto differs = [](const std::string& field, const std::string& arm_value,
                          const std::string& run_value, const std::string& option) {
    return "the arm's world has " + field + " " + arm_value + " but this run asks for " +
           run_value + " (start curio-sim serve with " + option + " " + run_value +
           ", or run curio-controller with " + option + " " + arm_value + ")";
  };
  if (arm.seed != asked.seed)
    return differs("seed", std::to_string(arm.seed), std::to_string(asked.seed), "--seed");
  if (arm.grasp_radius_bits != asked.grasp_radius_bits)
    return differs("grasp radius", number(bits_double(arm.grasp_radius_bits)),
                   number(bits_double(asked.grasp_radius_bits)), "--grasp-radius");
  if (arm.distractor_noise_bits != asked.distractor_noise_bits)
    return differs("distractor noise", number(bits_double(arm.distractor_noise_bits)),
                   number(bits_double(asked.distractor_noise_bits)), "--distractor-noise");
  if (arm.renderer_version != asked.renderer_version)
    return "the arm's world renders with renderer version " +
           std::to_string(arm.renderer_version) + " but this controller was built with version " +
           std::to_string(asked.renderer_version) + " (build curio-sim and curio-controller from "
           "one commit)";
  return "";
}

nlohmann::json world_json(const protocol::WorldIdentity& w) {
  return {{"physics", w.physics == od::kPhysicsOde ? "ode" : "kinematic"},
          {"seed", w.seed},
          {"grasp_radius", bits_double(w.grasp_radius_bits)},
          {"distractor_noise", bits_double(w.distractor_noise_bits)},
          {"renderer_version", w.renderer_version},
          {"hash", hex(protocol::world_hash(w))}};
}


bool bring_up_arm(hal::CanBus* bus, const ControllerConfig& config, Explorer& explorer,
                  nn::Encoder* encoder, CycleProbe* probe, const volatile int* stop_signal,
                  Controller& controller, BusRunResult* out) {
  lab::RunResult& r = out->run;
  if (const AppStatus s = controller.init(bus, &explorer, config, encoder); s != AppStatus::kOk) {
    r.error = std::string("controller init failed: ") + to_string(s);
    return false;
  }
  controller.set_cycle_probe(probe);
  controller.set_stop_request(stop_signal);
  const AppStatus started = controller.start_arm();
  for (int i = 0; i < kArmNodes; ++i) out->nodes[i] = controller.identity(i);
  out->identities_read = controller.identity(0).read;
  if (started != AppStatus::kOk) {
    const Fault fatal = controller.fatal_fault();
    r.error = fatal != Fault::kNone ? fatal_fault_text(controller.counters(), fatal)
                                    : bring_up_failure_text(controller.counters(), started);
    out->stop = controller.stop_arm();
    out->stopped = true;
    out->counters = controller.counters();
    return false;
  }
  out->physics = controller.query_physics();
  uint32_t indexed = 0;
  out->episode_indexed =
      controller.read_camera_object(protocol::od::kEpisodeControl, protocol::od::kEpisodeIndexedSub,
                                    &indexed) &&
      indexed == 1;
  if (std::string m = world_mismatch(controller, r.spec, &out->world, &out->world_published);
      !m.empty()) {
    r.error = m;
    out->stop = controller.stop_arm();
    out->stopped = true;
    out->counters = controller.counters();
    return false;
  }
  if (out->physics == 0) r.spec.physics = sim::Physics::kKinematic;
  if (out->physics == 1) r.spec.physics = sim::Physics::kOde;
  return true;
}

}  // namespace curio::app::host
