// meridian._core: the compiled half of the Python package meridian
// (python/meridian/__init__.py imports it; docs/python.md).

#include "bindings.hpp"

PYBIND11_MODULE(_core, m) {
  m.doc() = "Meridian's C++ library (use the package meridian, not this module)";
  meridian::python::register_errors();
  auto gravity = m.def_submodule("gravity", "gravity models and their batch evaluation");
  meridian::python::bind_gravity(gravity);
  auto gyro = m.def_submodule("gyro", "gyro-theodolite reductions");
  meridian::python::bind_gyro(gyro);
  auto angle = m.def_submodule("angle", "sexagesimal angles");
  meridian::python::bind_angle(angle);
  auto maglev = m.def_submodule("maglev", "maglev gyro workflows");
  meridian::python::bind_maglev(maglev);
  auto dov = m.def_submodule("dov", "dynamic deflection of the vertical");
  meridian::python::bind_dov(dov);
  auto nav = m.def_submodule("nav", "marine navigation post-processing");
  meridian::python::bind_nav(nav);
}
