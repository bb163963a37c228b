#pragma once
// numpy ⇄ std::vector for the bindings of python/src/: the Python wrappers
// (python/meridian/*.py) hand over contiguous float64 arrays of the shapes they
// checked; these helpers convert and check once more, so a direct call of
// meridian._core cannot crash.

#include <pybind11/numpy.h>

#include <cstddef>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::python {

using Array = pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast>;

/// The elements of a 1-D array; InputError (field `name`) for another number of dimensions.
inline std::vector<double> to_vector(const Array& a, const std::string& name) {
  if (a.ndim() != 1)
    throw InputError(fmt::format("must be 1-D, has {} dimensions", a.ndim()),
                     {"", std::nullopt, name});
  return {a.data(), a.data() + a.shape(0)};
}

/// A new 1-D float64 array holding `v`.
inline pybind11::array_t<double> to_numpy(const std::vector<double>& v) {
  pybind11::array_t<double> a(static_cast<pybind11::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

}  // namespace meridian::python
