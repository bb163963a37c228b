#pragma once
// The pieces of the extension module meridian._core, one function per library
// module (python/src/<module>.cpp); module.cpp calls each. Adding a module to
// the Python package is one such file, one line in module.cpp and a
// python/meridian/<module>.py that gives it its Pythonic face.

#include <pybind11/pybind11.h>

namespace meridian::python {

/// Translate meridian::Error (and its subclasses) to the Python classes of
/// meridian.errors with message, file, line and field attributes.
void register_errors();

/// meridian._core.gravity: the gravity model and its batch evaluation.
void bind_gravity(pybind11::module_& m);

/// meridian._core.gyro: reduce files (as the CLI's `gyro reduce`/`gyro campaign`).
void bind_gyro(pybind11::module_& m);

/// meridian._core.angle: DMS parsing and formatting (core/dms.hpp).
void bind_angle(pybind11::module_& m);

/// meridian._core.maglev: maglev gyro reduce, denoise, calibrate, simulate.
void bind_maglev(pybind11::module_& m);

/// meridian._core.dov: dynamic deflection of the vertical, process and simulate.
void bind_dov(pybind11::module_& m);

/// meridian._core.nav: marine navigation, process and simulate.
void bind_nav(pybind11::module_& m);

}  // namespace meridian::python
