// Shared pieces of the _curio module (docs/python.md): argument checks that raise
// ValueError / TypeError naming the argument, numpy views of C++ memory, and the classes the
// bindings share (a World is run by an Explorer; an Explorer's learned goal space encodes).
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sim/world.hpp"

namespace curio::python {

namespace py = pybind11;

// Raises ValueError("<arg>: <what>").
[[noreturn]] inline void value_error(const std::string& arg, const std::string& what) {
  throw py::value_error(arg + ": " + what);
}
[[noreturn]] inline void type_error(const std::string& arg, const std::string& what) {
  throw py::type_error(arg + ": " + what);
}

// A 1-D float vector of exactly `n` finite values from any array-like of numbers (lists,
// float32/float64 arrays); ValueError naming `arg` otherwise.
std::vector<float> finite_vector(const py::handle& obj, int n, const std::string& arg);

// `obj` as a C-contiguous uint8 array of shape (64, 64, 3) or (N, 64, 64, 3) (single → N = 1);
// TypeError for another dtype, ValueError for another shape.
py::array_t<uint8_t, py::array::c_style> camera_images(const py::handle& obj, const std::string& arg,
                                                       bool* single);

// A read-only numpy array over memory owned by `owner` (no copy): it keeps `owner` alive.
template <typename T>
py::array readonly_view(const T* data, std::vector<py::ssize_t> shape,
                        std::vector<py::ssize_t> strides_bytes, const py::handle& owner) {
  py::array a = data == nullptr  // an empty buffer: an empty array of its own
                    ? py::array(py::dtype::of<T>(), std::move(shape), std::move(strides_bytes))
                    : py::array(py::dtype::of<T>(), std::move(shape), std::move(strides_bytes), data, owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// curio.World: one Arm-2-Balls world (world_binding.cpp).
class PyWorld {
 public:
  PyWorld(const std::string& physics, uint64_t seed, double grasp_radius, double distractor_noise);
  sim::World& world();  // ValueError once closed, or while a call without the GIL uses it
  void close() {
    world();  // not while in use
    world_.reset();
  }
  bool closed() const { return !world_; }
  sim::Physics physics() const { return physics_; }
  uint64_t seed() const { return seed_; }

  // Held (under the GIL) by a call that uses the world with the GIL released: another call on
  // this world meanwhile, from another thread, raises ValueError instead of racing.
  class InUse {
   public:
    explicit InUse(PyWorld& w) : w_(w.check_free()) { w_.busy_ = true; }
    ~InUse() { w_.busy_ = false; }
    InUse(const InUse&) = delete;
    InUse& operator=(const InUse&) = delete;

   private:
    PyWorld& w_;
  };

 private:
  PyWorld& check_free();
  bool busy_ = false;
  std::unique_ptr<sim::World> world_;
  sim::Physics physics_;
  uint64_t seed_;
};

void bind_explorer(py::module_& m);
void bind_world(py::module_& m);
void bind_encoder(py::module_& m);
void bind_campaign(py::module_& m);

}  // namespace curio::python
