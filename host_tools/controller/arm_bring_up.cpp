#include "host_tools/controller/arm_bring_up.hpp"

#include "firmware/protocol/arm_objects.hpp"
#include "host_tools/controller/arm_world.hpp"
#include "host_tools/controller/fault_text.hpp"

namespace curio::app::host {

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
