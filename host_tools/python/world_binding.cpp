// curio.World: the Arm-2-Balls world (sim/world.hpp), kinematic or ODE, in a Gymnasium-like
// face: reset(), step(commands) one control period, run(theta) one whole episode as curio-lab
// runs it, render() the camera frame the controller receives.
#include <cmath>

#include "host_tools/experiment/run.hpp"
#include "host_tools/python/bindings.hpp"
#include "sim/camera.hpp"
#include "sim/render.hpp"

namespace curio::python {

PyWorld::PyWorld(const std::string& physics, uint64_t seed, double grasp_radius,
                 double distractor_noise)
    : seed_(seed) {
  if (!sim::parse_physics(physics, &physics_))
    value_error("physics", "expected 'kinematic' or 'ode', got '" + physics + "'");
  if (!(grasp_radius > 0.0) || !std::isfinite(grasp_radius))
    value_error("grasp_radius", "expected a finite number > 0");
  if (!(distractor_noise >= 0.0) || !std::isfinite(distractor_noise))
    value_error("distractor_noise", "expected a finite number >= 0");
  sim::WorldParams params;
  params.grasp_radius = grasp_radius;
  params.distractor_noise = distractor_noise;
  world_ = sim::make_world(physics_, params, lab::world_seed(seed));
}

PyWorld& PyWorld::check_free() {
  if (!world_) throw py::value_error("world: used after close()");
  if (busy_) throw py::value_error("world: in use by a call in another thread");
  return *this;
}

sim::World& PyWorld::world() { return *check_free().world_; }

namespace {

py::dict state_dict(const sim::SceneState& s) {
  py::dict d;
  d["hand"] = py::make_tuple(s.hand.x, s.hand.y);
  d["ball"] = py::make_tuple(s.ball.x, s.ball.y);
  d["distractor"] = py::make_tuple(s.distractor.x, s.distractor.y);
  d["grasped"] = s.grasped;
  return d;
}

// The engineered-feature outcome of a state, in the explorer's order: [distractor x,
// distractor y, ball x, ball y] as float32 (firmware/app/episode_outcome.hpp's conversion).
py::array_t<float> efr_outcome(const sim::SceneState& s) {
  py::array_t<float> out(4);
  float* o = out.mutable_data();
  o[0] = static_cast<float>(s.distractor.x);
  o[1] = static_cast<float>(s.distractor.y);
  o[2] = static_cast<float>(s.ball.x);
  o[3] = static_cast<float>(s.ball.y);
  return out;
}

py::array_t<uint8_t> camera_frame(const sim::Vec2& ball, const sim::Vec2& distractor) {
  sim::Image image;
  sim::render_scene(ball, distractor, &image);
  py::array_t<uint8_t> out({sim::kImageSize, sim::kImageSize, sim::kImageChannels});
  sim::to_camera_frame(image.data(), out.mutable_data());
  return out;
}

}  // namespace

void bind_world(py::module_& m) {
  py::class_<PyWorld>(m, "World", R"doc(
The Arm-2-Balls world: a 7-joint planar arm, a ball it can grasp and a distractor on a
random walk, with the kinematic model of the paper or the ODE arm.

World(physics="kinematic", seed=0, grasp_radius=0.1, distractor_noise=0.1)

`seed` is a run seed: World(seed=s) is the world curio-lab pairs with the run of seed s (its
distractor walk), so Explorer(seed=s).run(World(seed=s)) is curio-lab's run bit for bit.
Episodes advance the distractor's random stream; reset_to_episode(n) positions it.
)doc")
      .def(py::init<const std::string&, uint64_t, double, double>(),
           py::arg("physics") = "kinematic", py::arg("seed") = 0, py::arg("grasp_radius") = 0.1,
           py::arg("distractor_noise") = 0.1)
      .def_property_readonly("physics", [](const PyWorld& w) { return sim::physics_name(w.physics()); })
      .def_property_readonly("seed", &PyWorld::seed)
      .def_property_readonly("closed", &PyWorld::closed)
      .def(
          "reset",
          [](PyWorld& w) {
            w.world().reset();
            return state_dict(w.world().state());
          },
          "Starts an episode (arm at zero, ball at (0.6, 0.6), distractor at (0.7, -0.45)); "
          "returns the state dict.")
      .def(
          "reset_to_episode",
          [](PyWorld& w, int64_t episode) {
            if (episode < 0) value_error("episode", "expected a number >= 0");
            w.world().reset_to_episode(static_cast<uint64_t>(episode));
            return state_dict(w.world().state());
          },
          py::arg("episode"),
          "reset() for episode `episode` of the run: the distractor's random stream where that "
          "many 50-step episodes leave it.")
      .def(
          "step",
          [](PyWorld& w, const py::object& commands) {
            const auto c = finite_vector(commands, kJoints, "commands");
            for (float v : c)
              if (v < -1.0f || v > 1.0f) value_error("commands", "each value must be in [-1, 1]");
            w.world().step(c.data());
            return state_dict(w.world().state());
          },
          py::arg("commands"),
          "One control period (10 ms) with 7 joint commands in [-1, 1]; returns the state dict "
          "{'hand': (x, y), 'ball': (x, y), 'distractor': (x, y), 'grasped': bool}.")
      .def(
          "run",
          [](PyWorld& w, const py::object& theta) {
            const auto t = finite_vector(theta, kThetaDim, "theta");
            sim::World& world = w.world();
            sim::SceneState s;
            {
              const PyWorld::InUse in_use(w);
              py::gil_scoped_release release;
              s = world.rollout_joint_targets(t.data());
            }
            return efr_outcome(s);
          },
          py::arg("theta"),
          "One episode: reset(), then the 50 control periods of the motor primitive of theta "
          "(49 RBF weights), joint targets quantized as the controller sends them (what "
          "curio-lab runs). Returns the engineered-feature outcome, float32 [distractor x, "
          "distractor y, ball x, ball y]; `state` has the whole final state.")
      .def_property_readonly(
          "state", [](PyWorld& w) { return state_dict(w.world().state()); },
          "The current state: {'hand': (x, y), 'ball': (x, y), 'distractor': (x, y), "
          "'grasped': bool} (float64 positions).")
      .def(
          "render",
          [](PyWorld& w) {
            const sim::SceneState& s = w.world().state();
            return camera_frame(s.ball, s.distractor);
          },
          "The 64x64x3 uint8 image of the current state, the camera frame the controller "
          "receives (sim/render.hpp, then round(255 v)).")
      .def("close", &PyWorld::close, "Frees the world; any later use raises ValueError.")
      .def("__enter__", [](PyWorld& w) -> PyWorld& { return w; }, py::return_value_policy::reference)
      .def("__exit__", [](PyWorld& w, const py::args&) { w.close(); })
      .def("__repr__", [](const PyWorld& w) {
        return std::string("curio.World(physics='") + sim::physics_name(w.physics()) +
               "', seed=" + std::to_string(w.seed()) + (w.closed() ? ", closed)" : ")");
      });

  m.def(
      "render",
      [](const py::object& ball, const py::object& distractor) {
        const auto b = finite_vector(ball, 2, "ball");
        const auto d = finite_vector(distractor, 2, "distractor");
        return camera_frame({b[0], b[1]}, {d[0], d[1]});
      },
      py::arg("ball"), py::arg("distractor"),
      "The 64x64x3 uint8 camera frame of a scene with the ball and the distractor at these "
      "(x, y) positions.");
}

}  // namespace curio::python
