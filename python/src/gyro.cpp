// meridian._core.gyro: a reduce, campaign or stochastic-analysis file run as the CLI runs it
// (io/gyro_jobs.hpp), the result as the CLI's --json text (report/gyro_json.hpp,
// report/gyro_stochastic.hpp; the keys documented in docs/file-formats.md), compact
// (report::json_compact); python/meridian/gyro.py turns it into result objects.

#include <pybind11/stl.h>

#include <string>

#include "bindings.hpp"
#include "meridian/io/gyro_jobs.hpp"
#include "meridian/report/gyro_json.hpp"
#include "meridian/report/gyro_stochastic.hpp"
#include "meridian/report/json_text.hpp"

namespace py = pybind11;

namespace meridian::python {

void bind_gyro(py::module_& m) {
  m.def(
      "reduce_file",
      [](const std::string& path) {
        py::gil_scoped_release released;
        return report::json_compact(report::reduce_to_json(io::run_reduce_file(path).result));
      },
      py::arg("path"), "`meridian gyro reduce FILE --json` as JSON text");
  m.def(
      "campaign_file",
      [](const std::string& path) {
        py::gil_scoped_release released;
        return report::json_compact(report::campaign_to_json(io::run_campaign_file(path).result));
      },
      py::arg("path"), "`meridian gyro campaign FILE --json` as JSON text");
  m.def(
      "stochastic_file",
      [](const std::string& path) {
        py::gil_scoped_release released;
        return report::json_compact(report::stochastic_to_json(io::run_stochastic_file(path)));
      },
      py::arg("path"), "`meridian gyro stochastic FILE --json` as JSON text");
}

}  // namespace meridian::python
