#include "host_tools/controller/arm_bring_up.hpp"

#include "firmware/protocol/arm_objects.hpp"

namespace curio::app::host {

std::string seed_mismatch(Controller& controller, int64_t run_seed) {
  uint32_t arm_seed = 0;
  if (!controller.read_camera_object(protocol::od::kRunSeed, 0, &arm_seed)) return "";
  if (arm_seed == static_cast<uint32_t>(run_seed)) return "";
  return "the arm's world runs seed " + std::to_string(arm_seed) + " but this run is seed " +
         std::to_string(run_seed) + " (start curio-sim serve with --seed " +
         std::to_string(run_seed) + ")";
}

bool bring_up_arm(hal::CanBus* bus, const ControllerConfig& config, Explorer& explorer,
                  nn::Encoder* encoder, CycleProbe* probe, Controller& controller,
                  BusRunResult* out) {
  lab::RunResult& r = out->run;
  if (const AppStatus s = controller.init(bus, &explorer, config, encoder); s != AppStatus::kOk) {
    r.error = std::string("controller init failed: ") + to_string(s);
    return false;
  }
  controller.set_cycle_probe(probe);
  if (const AppStatus s = controller.start_arm(); s != AppStatus::kOk) {
    const Fault fatal = controller.fatal_fault();
    r.error = fatal != Fault::kNone ? fatal_fault_text(controller.counters(), fatal)
                                    : std::string("the arm did not come up: ") + to_string(s) +
                                          " (" + fault_summary(controller.counters()) +
                                          "); is `curio-sim serve` running on this bus?";
    out->counters = controller.counters();
    return false;
  }
  out->physics = controller.query_physics();
  uint32_t indexed = 0;
  out->episode_indexed =
      controller.read_camera_object(protocol::od::kEpisodeControl, protocol::od::kEpisodeIndexedSub,
                                    &indexed) &&
      indexed == 1;
  if (std::string m = seed_mismatch(controller, r.spec.explorer.seed); !m.empty()) {
    r.error = m;
    controller.stop_arm();
    out->counters = controller.counters();
    return false;
  }
  if (out->physics == 0) r.spec.physics = sim::Physics::kKinematic;
  if (out->physics == 1) r.spec.physics = sim::Physics::kOde;
  return true;
}

}  // namespace curio::app::host
