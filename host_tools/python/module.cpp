// The _curio extension module: the C++ half of the `curio` Python package (docs/python.md).
#include "host_tools/python/bindings.hpp"

#include <cmath>

#include "firmware/explore/config.hpp"
#include "sim/render.hpp"

namespace curio::python {

std::vector<float> finite_vector(const py::handle& obj, int n, const std::string& arg) {
  py::array_t<float, py::array::c_style | py::array::forcecast> a;
  try {
    a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(obj);
  } catch (const py::error_already_set&) {
    a = {};
  }
  if (!a) type_error(arg, "expected a vector of numbers");
  if (a.ndim() != 1 || a.shape(0) != n)
    value_error(arg, "expected a vector of " + std::to_string(n) + " values, got shape " +
                         std::string(py::str(py::tuple(py::cast(std::vector<py::ssize_t>(
                             a.shape(), a.shape() + a.ndim()))))));
  std::vector<float> v(a.data(), a.data() + n);
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(v[static_cast<size_t>(i)]))
      value_error(arg, "value " + std::to_string(i) + " is not finite");
  return v;
}

py::array_t<uint8_t, py::array::c_style> camera_images(const py::handle& obj, const std::string& arg,
                                                       bool* single) {
  if (!py::isinstance<py::array>(obj))
    type_error(arg, "expected a numpy uint8 array of shape (64, 64, 3) or (N, 64, 64, 3)");
  const auto a = py::reinterpret_borrow<py::array>(obj);
  if (!a.dtype().is(py::dtype::of<uint8_t>()))
    type_error(arg, "expected dtype uint8 (camera bytes 0..255), got " +
                        std::string(py::str(a.dtype())));
  const bool one = a.ndim() == 3;
  const int lead = one ? 0 : 1;
  if ((a.ndim() != 3 && a.ndim() != 4) || a.shape(lead) != sim::kImageSize ||
      a.shape(lead + 1) != sim::kImageSize || a.shape(lead + 2) != sim::kImageChannels)
    value_error(arg, "expected shape (64, 64, 3) or (N, 64, 64, 3), got " +
                         std::string(py::str(obj.attr("shape"))));
  *single = one;
  return py::array_t<uint8_t, py::array::c_style>::ensure(a);
}

}  // namespace curio::python

PYBIND11_MODULE(_curio, m) {
  using namespace curio::python;
  m.doc() =
      "Curio's C++ core: the firmware Explorer (RPE, RGE, MGE), the Arm-2-Balls worlds, the "
      "int8 encoder and in-process campaigns. Use it through the `curio` package.";
  m.attr("THETA_DIM") = curio::kThetaDim;
  m.attr("MAX_OUTCOME_DIM") = curio::kMaxOutcomeDim;
  m.attr("ARCHIVE_CAPACITY") = curio::kArchiveCapacity;
  m.attr("IMAGE_SIZE") = curio::sim::kImageSize;
  bind_world(m);
  bind_explorer(m);
  bind_encoder(m);
  bind_campaign(m);
}
