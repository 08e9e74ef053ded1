// The compiled part of the `oceanref` Python package (oceanref._core): errors, build facts and
// the registration of every concept's bindings.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <thread>

#include "build_info.h"
#include "common.h"
#include "conformance/provenance.h"
#include "core/direction.h"
#include "scene/scene.h"
#include "spectrum/model.h"

namespace oceanref::python {

py::array_t<double> to_array(const std::vector<double>& values,
                             const std::vector<py::ssize_t>& shape) {
  py::array_t<double> out(shape);
  double* data = out.mutable_data();
  for (std::size_t i = 0; i < values.size(); ++i) data[i] = values[i];
  return out;
}

std::array<double, 3> unit_vector(const std::string& key, const py::handle& value) {
  const DoubleArray a = DoubleArray::ensure(value);
  if (!a || a.size() != 3) throw ArgumentError(key, "expected a direction x,y,z (3 numbers)");
  const double* v = a.data();
  for (py::ssize_t i = 0; i < 3; ++i) {
    if (!(v[i] - v[i] == 0.0)) throw ArgumentError(key, "expected finite numbers");
  }
  const std::optional<std::array<double, 3>> d = unit_direction({v[0], v[1], v[2]});
  if (!d) throw ArgumentError(key, "the vector must not be zero");
  return *d;
}

int resolve_threads(int requested) {
  if (requested < 0 || requested > 1024) {
    throw ArgumentError("threads",
                        "must be in [0, 1024] (0: all cores), got " + std::to_string(requested));
  }
  return requested > 0 ? requested
                       : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

std::string format_number(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

}  // namespace oceanref::python

PYBIND11_MODULE(_core, m) {
  namespace py = pybind11;
  using namespace oceanref::python;
  m.doc() =
      "oceanref's library bindings (use the `oceanref` package, which wraps them with NumPy "
      "conveniences).";
  // Invalid settings and scene values are the user's input: ValueError, with the key (or JSON
  // path) and the accepted range, as the command line prints them.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const oceanref::SceneError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const oceanref::SettingError& e) {
      PyErr_SetString(PyExc_ValueError, (e.key() + ": " + e.what()).c_str());
    }
  });
  m.attr("__version__") = OCEANREF_PY_VERSION;
  py::dict info;
  info["version"] = "oceanref " OCEANREF_PY_VERSION;
  info["commit"] = oceanref::oceanref_commit();  // as `oceanref --version` (build time)
  info["compiler"] = OCEANREF_PY_COMPILER;
  info["build_type"] = OCEANREF_PY_BUILD_TYPE;
  info["flags"] = OCEANREF_PY_FLAGS;
  info["math_library"] = OCEANREF_PY_MATH;
  info["python"] = OCEANREF_PY_PYTHON;
  info["pybind11"] = OCEANREF_PY_PYBIND11;
  m.attr("_build_info") = info;
  bind_spectrum(m);
  bind_scene(m);
  bind_lighting(m);
  bind_compare(m);
}
