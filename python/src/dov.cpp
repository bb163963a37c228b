// meridian._core.dov: the dynamic deflection of the vertical as `meridian dov` runs it
// (apps/meridian/cmd_dov.cpp), through the same runners and writers: a configuration and its
// line file (io::run_dov_stream), or a line given as arrays with a configuration's options
// (io::run_dov_columns); the summary as JSON text (report::dov_summary_to_json,
// report::json_compact) and the profile as arrays named like the columns of `dov process -o`
// (report::dov_profile_columns, dov_profile_values). The simulator's line and a line file come
// back as the arrays of io::dov_line_columns (degrees, arc-seconds, the attitude matrices as
// (n, 3, 3)). python/meridian/dov.py gives them their face.

#include <pybind11/stl.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "meridian/core/units.hpp"
#include "meridian/dov/deflection.hpp"
#include "meridian/dov/simulator.hpp"
#include "meridian/io/dov_columns.hpp"
#include "meridian/io/dov_files.hpp"
#include "meridian/io/dov_jobs.hpp"
#include "meridian/report/dov_outputs.hpp"
#include "meridian/report/json_text.hpp"

namespace py = pybind11;

namespace meridian::python {
namespace {

namespace md = meridian::dov;

// Collects the epochs' profile columns (the GIL released: plain vectors only).
struct Profile {
  std::array<std::vector<double>, report::kDovProfileColumns> columns;
  std::size_t count = report::dov_profile_column_count(false);
  void add(const md::EpochResult& e) {
    const std::array<double, report::kDovProfileColumns> v = report::dov_profile_values(e);
    count = report::dov_profile_column_count(e.truth.has_value());
    for (std::size_t i = 0; i < count; ++i) columns[i].push_back(v[i]);
  }
  py::dict to_dict() const {
    py::dict d;
    for (std::size_t i = 0; i < count; ++i)
      d[report::dov_profile_columns()[i]] = to_numpy(columns[i]);
    return d;
  }
};

py::tuple process_file(const std::string& config) {
  Profile profile;
  std::string text;
  {
    py::gil_scoped_release released;
    const io::DovConfig c = io::read_dov_config(config);
    const md::Result r =
        io::run_dov_stream(c, {[&](const md::EpochResult& e) { profile.add(e); }});
    text = report::json_compact(report::dov_summary_to_json(r));
  }
  return py::make_tuple(text, profile.to_dict());
}

using Matrices = py::array_t<double, py::array::c_style | py::array::forcecast>;

// The (n, 3, 3) matrices of `name`, row by row.
std::vector<double> matrices_of(const py::dict& line, const char* name) {
  const Matrices m = line[name].cast<Matrices>();
  if (m.ndim() != 3 || m.shape(1) != 3 || m.shape(2) != 3)
    throw InputError("must have the shape (n, 3, 3)", {"", std::nullopt, name});
  return {m.data(), m.data() + m.size()};
}

// The arrays of a line (checked by dov.py) as io's columns.
io::DovLineColumns columns_of(const py::dict& line) {
  auto column = [&](const char* name) { return to_vector(line[name].cast<Array>(), name); };
  io::DovLineColumns c;
  c.time_s = column("time_s");
  c.lat_deg = column("lat_deg");
  c.lon_deg = column("lon_deg");
  c.height_m = column("height_m");
  c.speed_m_s = column("speed_m_s");
  c.model_eta_arcsec = column("model_eta_arcsec");
  c.model_xi_arcsec = column("model_xi_arcsec");
  c.lgu_body_to_nav = matrices_of(line, "lgu_body_to_nav");
  c.ins_body_to_nav = matrices_of(line, "ins_body_to_nav");
  c.has_truth = line.contains("truth_eta_arcsec");
  if (c.has_truth) {
    c.truth_eta_arcsec = column("truth_eta_arcsec");
    c.truth_xi_arcsec = column("truth_xi_arcsec");
  }
  return c;
}

// A line as arrays with the options of the configuration `options_file` (its `line:` is not
// read); a configuration that names a gravity model is refused (the arrays carry η_G, ξ_G).
py::tuple process_arrays(const py::dict& line, const std::string& options_file) {
  const io::DovLineColumns columns = columns_of(line);
  Profile profile;
  std::string text;
  {
    py::gil_scoped_release released;
    const md::Result r = io::run_dov_columns(columns, options_file);
    for (const md::EpochResult& e : r.epochs) profile.add(e);
    text = report::json_compact(report::dov_summary_to_json(r));
  }
  return py::make_tuple(text, profile.to_dict());
}

// A new (n, 3, 3) array of matrices given row by row.
py::array_t<double> matrices_array(const std::vector<double>& v) {
  const std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(v.size() / 9), 3, 3};
  py::array_t<double> a(shape);
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

// io's columns as the arrays of a line: the model and truth columns when the line has them.
py::dict line_dict(const io::DovLineColumns& c) {
  py::dict d;
  d["time_s"] = to_numpy(c.time_s);
  d["lat_deg"] = to_numpy(c.lat_deg);
  d["lon_deg"] = to_numpy(c.lon_deg);
  d["height_m"] = to_numpy(c.height_m);
  d["speed_m_s"] = to_numpy(c.speed_m_s);
  d["lgu_body_to_nav"] = matrices_array(c.lgu_body_to_nav);
  d["ins_body_to_nav"] = matrices_array(c.ins_body_to_nav);
  if (c.has_model) {
    d["model_eta_arcsec"] = to_numpy(c.model_eta_arcsec);
    d["model_xi_arcsec"] = to_numpy(c.model_xi_arcsec);
  }
  if (c.has_truth) {
    d["truth_eta_arcsec"] = to_numpy(c.truth_eta_arcsec);
    d["truth_xi_arcsec"] = to_numpy(c.truth_xi_arcsec);
  }
  return d;
}

py::dict simulate(const py::dict& o) {
  md::SimulationOptions so;
  so.start_lat_rad = units::deg_to_rad(o["latitude_deg"].cast<double>());
  so.start_lon_rad = units::deg_to_rad(o["longitude_deg"].cast<double>());
  so.heading_rad = units::deg_to_rad(o["heading_deg"].cast<double>());
  so.height_m = o["height_m"].cast<double>();
  so.speed_m_s = o["speed_m_s"].cast<double>();
  so.rate_hz = o["rate_hz"].cast<double>();
  so.duration_s = o["hours"].cast<double>() * 3600.0;
  so.truth_model.sigma_model_rad = units::arcsec_to_rad(o["sigma_model_arcsec"].cast<double>());
  so.sigma_ins_rad = units::arcsec_to_rad(o["sigma_ins_arcsec"].cast<double>());
  so.eps_u_rad_s = units::deg_to_rad(o["eps_u_deg_per_h"].cast<double>()) / 3600.0;
  so.initial_attitude_error_rad =
      Eigen::Vector3d(o["phi_e_arcsec"].cast<double>(), o["phi_n_arcsec"].cast<double>(),
                      o["phi_u_arcsec"].cast<double>()) *
      units::kArcsecond;
  so.seed = o["seed"].cast<std::uint64_t>();
  so.transport_rate = o["transport_rate"].cast<bool>();
  io::DovLineColumns columns;
  {
    py::gil_scoped_release released;
    const md::Input in = md::simulate(so);
    columns = io::dov_line_columns(in.samples, in.truth, true);
  }
  return line_dict(columns);
}

// A line file (CSV or binary, by content) read whole, as the columns simulate() gives: the
// model columns only when the file has them, the truth columns only when it has them.
// Also the header's columns the reader does not use (a misspelt optional column), for a warning.
py::tuple read_line(const std::string& path) {
  io::DovLineColumns columns;
  std::vector<std::string> ignored;
  {
    py::gil_scoped_release released;
    const io::DovLine line = io::read_dov_line_file(path);
    columns = io::dov_line_columns(line.samples, line.truth, line.has_model_values);
    ignored = line.ignored_columns;
  }
  return py::make_tuple(line_dict(columns), ignored);
}

}  // namespace

void bind_dov(py::module_& m) {
  m.def("process_file", &process_file, py::arg("config"),
        "`dov process CONFIG --json -o profile.csv`: (JSON text, profile columns)");
  m.def("process_arrays", &process_arrays, py::arg("line"), py::arg("options_file"),
        "A line of arrays with the options of a configuration file: (JSON text, profile columns)");
  m.def("simulate", &simulate, py::arg("options"), "`dov simulate`: the line's columns");
  m.def("read_line", &read_line, py::arg("path"),
        "A line file (CSV or binary) as the columns simulate gives, and the columns not used");
}

}  // namespace meridian::python
