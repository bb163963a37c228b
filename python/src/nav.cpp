// meridian._core.nav: marine navigation as `meridian nav` runs it (apps/meridian/cmd_nav.cpp):
// a configuration with its DR/LOP/fix CSVs or NMEA logs through the runner io::run_nav, the
// summary as the CLI's --json (report/nav_outputs.hpp, report::json_compact) and every method's
// track as the arrays of report::nav_track_columns, the columns of `nav process -o`;
// the simulator writes the files of `nav simulate --out DIR`. python/meridian/nav.py gives
// them their Python face.

#include <pybind11/stl.h>

#include <algorithm>
#include <string>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "meridian/io/nav_files.hpp"
#include "meridian/io/nmea.hpp"
#include "meridian/nav/navigation.hpp"
#include "meridian/nav/simulator.hpp"
#include "meridian/report/json_text.hpp"
#include "meridian/report/nav_inspect.hpp"
#include "meridian/report/nav_outputs.hpp"

namespace py = pybind11;

namespace meridian::python {
namespace {

namespace mn = meridian::nav;

// A method's track: the columns of report::nav_track_columns, a σ of the bias that the method
// does not state NaN (as the JSON summary's null).
py::dict track(const mn::Result& r, mn::Method method) {
  const report::NavTrackColumns c = report::nav_track_columns(r, method, true);
  py::dict d;
  for (std::size_t i = 0; i < c.names.size(); ++i) d[py::str(c.names[i])] = to_numpy(c.values[i]);
  py::array_t<unsigned> flags(static_cast<py::ssize_t>(c.flags.size()));
  std::copy(c.flags.begin(), c.flags.end(), flags.mutable_data());
  d["flags"] = flags;
  return d;
}

// (JSON text, [(method name, track columns)] in the result's order).
py::tuple process_file(const std::string& config) {
  mn::Result result;
  std::string text;
  {
    py::gil_scoped_release released;
    result = io::run_nav(io::read_nav_config(config)).result;
    text = report::json_compact(report::nav_to_json(result));
  }
  py::list tracks;
  for (const mn::MethodResult& m : result.methods)
    tracks.append(py::make_tuple(mn::to_string(m.method), track(result, m.method)));
  return py::make_tuple(text, tracks);
}

}  // namespace

void bind_nav(py::module_& m) {
  m.def(
      "inspect_files",
      [](const std::vector<std::string>& files, bool accept_missing_checksum) {
        py::gil_scoped_release released;
        return report::json_compact(
            report::nav_inspect_files_to_json(io::nmea::inspect_files(files, accept_missing_checksum)));
      },
      py::arg("files"), py::arg("accept_missing_checksum"),
      "`nav inspect FILE... --json` as JSON text");
  m.def("process_file", &process_file, py::arg("config"),
        "`nav process CONFIG --json` and every method's track: (JSON text, [(method, columns)])");
  m.def(
      "simulate",
      [](const std::string& out, const std::string& scenario, std::uint64_t seed, int stations,
         double duration_s, double fixes_every_s) {
        py::gil_scoped_release released;
        mn::SimulationOptions so;
        so.scenario = mn::scenario_from_string(scenario);
        so.seed = seed;
        so.stations = stations;
        so.duration_s = duration_s;
        so.fix_interval_s = fixes_every_s;
        const mn::SimulatedLine line = mn::simulate(so);
        return std::make_tuple(io::write_nav_simulation(out, line, so), line.blunders,
                               line.settings);
      },
      py::arg("out"), py::arg("scenario"), py::arg("seed"), py::arg("stations"),
      py::arg("duration_s"), py::arg("fixes_every_s"),
      "`nav simulate --out DIR`: (files written, blunder LOP indices, settings)");
}

}  // namespace meridian::python
