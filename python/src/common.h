// Shared helpers of the Python bindings: NumPy conversion, argument checks with the CLI's
// messages ("KEY: message naming the accepted range"), and the registration functions of each
// concept's bindings (one file per concept, as Mitsuba's *_v.cpp).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace oceanref::python {

namespace py = pybind11;

// Bad input: becomes a Python ValueError "KEY: message".
class ArgumentError : public std::invalid_argument {
 public:
  ArgumentError(const std::string& key, const std::string& message)
      : std::invalid_argument(key + ": " + message) {}
};

// A contiguous float64 copy of any array-like (NumPy converts; ValueError when it cannot).
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// A new float64 array of the given shape holding `values` (row-major).
py::array_t<double> to_array(const std::vector<double>& values,
                             const std::vector<py::ssize_t>& shape);

// A direction x,y,z (normalized; a zero vector is rejected naming `key`).
std::array<double, 3> unit_vector(const std::string& key, const py::handle& value);

// 0 → every core; otherwise 1…1024 (as `--threads`).
int resolve_threads(int requested);

std::string format_number(double v);  // 17 significant digits, as the CLI prints

void bind_spectrum(py::module_& m);
void bind_scene(py::module_& m);
void bind_lighting(py::module_& m);
void bind_compare(py::module_& m);

}  // namespace oceanref::python
