// meridian._core.angle: sexagesimal notation (core/dms.hpp), in degrees.

#include <string>

#include "bindings.hpp"
#include "meridian/core/angle.hpp"
#include "meridian/core/dms.hpp"

namespace py = pybind11;

namespace meridian::python {

void bind_angle(py::module_& m) {
  m.def(
      "parse_deg", [](const std::string& text, const std::string& unit) {
        return parse_angle(text, angle_unit_from_string(unit)).deg();
      },
      py::arg("text"), py::arg("unit") = "dms", "parse_angle(text, unit) in decimal degrees");
  m.def(
      "format_dms",
      [](double deg, int second_decimals, bool symbols, bool force_sign) {
        return format_dms(Angle::degrees(deg), DmsFormat{second_decimals, symbols, force_sign});
      },
      py::arg("deg"), py::arg("second_decimals") = 1, py::arg("symbols") = true, py::arg("force_sign") = false);
  m.def(
      "format_direction_dms",
      [](double deg, int second_decimals, bool symbols) {
        return format_direction_dms(Angle::degrees(deg), DmsFormat{second_decimals, symbols, false});
      },
      py::arg("deg"), py::arg("second_decimals") = 1, py::arg("symbols") = true);
  m.def(
      "format_ddd_mmss", [](double deg, int second_decimals) { return format_ddd_mmss(Angle::degrees(deg), second_decimals); },
      py::arg("deg"), py::arg("second_decimals") = 1);
}

}  // namespace meridian::python
