// meridian._core.nav: marine navigation as `meridian nav` runs it (apps/meridian/cmd_nav.cpp):
// a configuration with its DR/LOP/fix CSVs or NMEA logs through io::run_nav, the summary as
// the CLI's --json text (report/nav_outputs.hpp) and every method's track as arrays named like
// the columns of `nav process -o` (x north, y east in m; lat_deg, lon_deg with a projection);
// the simulator writes the files of `nav simulate --out DIR`. python/meridian/nav.py gives
// them their Python face.

#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "arrays.hpp"
#include "bindings.hpp"
#include "meridian/core/units.hpp"
#include "meridian/io/nav_files.hpp"
#include "meridian/io/nmea.hpp"
#include "meridian/nav/navigation.hpp"
#include "meridian/nav/simulator.hpp"
#include "meridian/report/nav_inspect.hpp"
#include "meridian/report/nav_outputs.hpp"

namespace py = pybind11;

namespace meridian::python {
namespace {

namespace mn = meridian::nav;

// A method's track: the columns of report::nav_track_csv. A σ of the bias that the method does
// not state (not finite or 0: methods I and II, and those without a bias) is NaN, as the JSON
// summary's null.
py::dict track(const mn::MethodResult& m, const io::NavToGeographic& to_geographic) {
  const std::size_t n = m.track.size();
  std::vector<double> t(n), x(n), y(n), lat(n), lon(n), sx(n), sy(n), cxy(n), bn(n), be(n), sbn(n),
      sbe(n);
  py::array_t<unsigned> flags(static_cast<py::ssize_t>(n));
  const auto stated = [](double sigma) {
    return std::isfinite(sigma) && sigma > 0.0 ? sigma : std::numeric_limits<double>::quiet_NaN();
  };
  for (std::size_t k = 0; k < n; ++k) {
    const mn::TrackPoint& p = m.track[k];
    t[k] = p.time_s;
    x[k] = p.x_north_m;
    y[k] = p.y_east_m;
    if (to_geographic) {
      const auto ll = to_geographic(p.x_north_m, p.y_east_m);
      lat[k] = units::rad_to_deg(ll[0]);
      lon[k] = units::rad_to_deg(ll[1]);
    }
    sx[k] = p.sigma_x_m();
    sy[k] = p.sigma_y_m();
    cxy[k] = p.covariance(0, 1);
    bn[k] = p.bias_north_m_s;
    be[k] = p.bias_east_m_s;
    sbn[k] = stated(p.sigma_bias_north_m_s);
    sbe[k] = stated(p.sigma_bias_east_m_s);
    flags.mutable_data()[k] = p.flags;
  }
  py::dict d;
  d["time_s"] = to_numpy(t);
  d["x_m"] = to_numpy(x);
  d["y_m"] = to_numpy(y);
  if (to_geographic) {
    d["lat_deg"] = to_numpy(lat);
    d["lon_deg"] = to_numpy(lon);
  }
  d["sigma_x_m"] = to_numpy(sx);
  d["sigma_y_m"] = to_numpy(sy);
  d["cov_xy_m2"] = to_numpy(cxy);
  d["bias_north_m_s"] = to_numpy(bn);
  d["bias_east_m_s"] = to_numpy(be);
  d["sigma_bias_north_m_s"] = to_numpy(sbn);
  d["sigma_bias_east_m_s"] = to_numpy(sbe);
  d["flags"] = flags;
  return d;
}

// (JSON text, [(method name, track columns)] in the result's order).
py::tuple process_file(const std::string& config) {
  io::NavRun run;
  std::string text;
  {
    py::gil_scoped_release released;
    run = io::run_nav(io::read_nav_config(config));
    text = report::nav_to_json(run.result)
               .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  }
  py::list tracks;
  for (const mn::MethodResult& m : run.result.methods)
    tracks.append(py::make_tuple(mn::to_string(m.method), track(m, run.to_geographic)));
  return py::make_tuple(text, tracks);
}

}  // namespace

void bind_nav(py::module_& m) {
  m.def(
      "inspect_files",
      [](const std::vector<std::string>& files, bool accept_missing_checksum) {
        py::gil_scoped_release released;
        io::nmea::Options o;
        o.accept_missing_checksum = accept_missing_checksum;
        nlohmann::json summaries = nlohmann::json::array();
        for (const std::string& f : files)
          summaries.push_back(report::nav_inspect_to_json(io::nmea::read_file(f, o)));
        return nlohmann::json{{"files", summaries}}.dump(-1, ' ', false,
                                                         nlohmann::json::error_handler_t::replace);
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
