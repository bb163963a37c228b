// meridian._core.dov: the dynamic deflection of the vertical as `meridian dov` runs it
// (apps/meridian/cmd_dov.cpp): a configuration and its line file, or a line given as
// arrays with a configuration's options, through io::run_dov_stream / dov::process;
// the summary as the CLI's --json text (report/dov_outputs.hpp) and the profile as
// arrays named like the columns of `dov process -o` (angles in arc-seconds, ε_U in °/h).
// The simulator's line comes back as the arrays of a line file (degrees, arc-seconds,
// the attitude matrices as (n, 3, 3)). python/meridian/dov.py gives them their face.

#include <pybind11/stl.h>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "arrays.hpp"
#include "bindings.hpp"
#include "meridian/core/units.hpp"
#include "meridian/dov/deflection.hpp"
#include "meridian/dov/simulator.hpp"
#include "meridian/dov/streaming.hpp"
#include "meridian/io/dov_files.hpp"
#include "meridian/report/dov_outputs.hpp"

namespace py = pybind11;

namespace meridian::python {
namespace {

namespace md = meridian::dov;
using units::rad_to_arcsec;

std::string json_text(const nlohmann::json& j) {
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// The profile's columns, in the order of report::dov_profile_csv_header.
constexpr std::array<const char*, 20> kProfile = {"time_s",
                                                  "lat_deg",
                                                  "lon_deg",
                                                  "model_eta_arcsec",
                                                  "model_xi_arcsec",
                                                  "filtered_eta_arcsec",
                                                  "filtered_xi_arcsec",
                                                  "filtered_sigma_eta_arcsec",
                                                  "filtered_sigma_xi_arcsec",
                                                  "smoothed_eta_arcsec",
                                                  "smoothed_xi_arcsec",
                                                  "smoothed_sigma_eta_arcsec",
                                                  "smoothed_sigma_xi_arcsec",
                                                  "filtered_eps_u_deg_per_h",
                                                  "innovation_east_arcsec",
                                                  "innovation_north_arcsec",
                                                  "nis",
                                                  "accepted",
                                                  "truth_eta_arcsec",
                                                  "truth_xi_arcsec"};

// Collects the epochs' profile columns (the GIL released: plain vectors only).
struct Profile {
  std::array<std::vector<double>, kProfile.size()> columns;
  bool truth = false;
  void add(const md::EpochResult& e) {
    const double deg_h = units::rad_to_deg(e.filtered.eps_u_rad_s) * 3600.0;
    const double v[] = {e.time_s,
                        units::rad_to_deg(e.lat_rad),
                        units::rad_to_deg(e.lon_rad),
                        rad_to_arcsec(e.model_eta_rad),
                        rad_to_arcsec(e.model_xi_rad),
                        rad_to_arcsec(e.filtered.eta_rad),
                        rad_to_arcsec(e.filtered.xi_rad),
                        rad_to_arcsec(e.filtered.sigma_eta_rad),
                        rad_to_arcsec(e.filtered.sigma_xi_rad),
                        rad_to_arcsec(e.smoothed.eta_rad),
                        rad_to_arcsec(e.smoothed.xi_rad),
                        rad_to_arcsec(e.smoothed.sigma_eta_rad),
                        rad_to_arcsec(e.smoothed.sigma_xi_rad),
                        deg_h,
                        rad_to_arcsec(e.innovation_east_rad),
                        rad_to_arcsec(e.innovation_north_rad),
                        e.nis,
                        e.accepted ? 1.0 : 0.0};
    for (std::size_t i = 0; i < std::size(v); ++i) columns[i].push_back(v[i]);
    truth = e.truth.has_value();
    if (truth) {
      columns[18].push_back(rad_to_arcsec(e.truth->eta_rad));
      columns[19].push_back(rad_to_arcsec(e.truth->xi_rad));
    }
  }
  py::dict to_dict() const {
    py::dict d;
    for (std::size_t i = 0; i < kProfile.size(); ++i)
      if (i < 18 || truth) d[kProfile[i]] = to_numpy(columns[i]);
    return d;
  }
};

py::tuple process_file(const std::string& config) {
  Profile profile;
  std::string text;
  {
    py::gil_scoped_release released;
    const io::DovConfig c = io::read_dov_config(config);
    const md::LineResult line =
        io::run_dov_stream(c, [&](const md::EpochResult& e) { profile.add(e); });
    md::Result r;
    r.summary = line.summary;
    r.notes = line.notes;
    r.warnings = line.warnings;
    text = json_text(report::dov_summary_to_json(r, c.options));
  }
  return py::make_tuple(text, profile.to_dict());
}

using Matrices = py::array_t<double, py::array::c_style | py::array::forcecast>;

// The samples of arrays of one length n (the (n, 3, 3) matrices checked by dov.py).
md::Input input_of(const py::dict& line) {
  auto column = [&](const char* name) { return to_vector(line[name].cast<Array>(), name); };
  const std::vector<double> t = column("time_s"), lat = column("lat_deg"), lon = column("lon_deg"),
                            h = column("height_m"), v = column("speed_m_s"),
                            eta = column("model_eta_arcsec"), xi = column("model_xi_arcsec");
  const std::size_t n = t.size();
  for (const auto* c : {&lat, &lon, &h, &v, &eta, &xi})
    if (c->size() != n)
      throw InputError("the line's arrays must have one length", {"", std::nullopt, "line"});
  auto matrices = [&](const char* name) {
    const Matrices m = line[name].cast<Matrices>();
    if (m.ndim() != 3 || static_cast<std::size_t>(m.shape(0)) != n || m.shape(1) != 3 ||
        m.shape(2) != 3)
      throw InputError("must have the shape (n, 3, 3)", {"", std::nullopt, name});
    return m;
  };
  const Matrices lgu = matrices("lgu_body_to_nav"), ins = matrices("ins_body_to_nav");
  md::Input in;
  in.samples.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    md::Sample& s = in.samples[k];
    s.time_s = t[k];
    s.lat_rad = units::deg_to_rad(lat[k]);
    s.lon_rad = units::deg_to_rad(lon[k]);
    s.height_m = h[k];
    s.speed_m_s = v[k];
    s.model_eta_rad = units::arcsec_to_rad(eta[k]);
    s.model_xi_rad = units::arcsec_to_rad(xi[k]);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        s.lgu_body_to_nav(i, j) = lgu.at(k, i, j);
        s.ins_body_to_nav(i, j) = ins.at(k, i, j);
      }
  }
  if (line.contains("truth_eta_arcsec")) {
    const std::vector<double> te = column("truth_eta_arcsec"), tx = column("truth_xi_arcsec");
    if (te.size() != n || tx.size() != n)
      throw InputError("the line's arrays must have one length", {"", std::nullopt, "line"});
    in.truth.resize(n);
    for (std::size_t k = 0; k < n; ++k)
      in.truth[k] = {units::arcsec_to_rad(te[k]), units::arcsec_to_rad(tx[k]), {}};
  }
  return in;
}

// A line as arrays with the options of the configuration `options_file` (its `line:` is
// not read); a configuration that names a gravity model is refused (the arrays carry η_G, ξ_G).
py::tuple process_arrays(const py::dict& line, const std::string& options_file) {
  md::Input in = input_of(line);
  Profile profile;
  std::string text;
  {
    py::gil_scoped_release released;
    const io::DovConfig c = io::read_dov_config(options_file);
    if (c.gravity_model)
      throw InputError(
          "a line given as arrays carries its model values (model_eta_arcsec, model_xi_arcsec): "
          "no gravity_model",
          {c.file, std::nullopt, "gravity_model"});
    in.options = c.options;
    const md::Result r = md::process(in);
    for (const md::EpochResult& e : r.epochs) profile.add(e);
    text = json_text(report::dov_summary_to_json(r, c.options));
  }
  return py::make_tuple(text, profile.to_dict());
}

// The columns of a line (dov simulate's Table, the CSV's names): model and truth columns
// when `model` / truth is not empty.
py::dict line_columns(const std::vector<md::Sample>& samples, const std::vector<md::Truth>& truth,
                      bool model) {
  const std::size_t n = samples.size();
  const bool has_truth = !truth.empty();
  std::vector<double> t(n), lat(n), lon(n), h(n), v(n), eta(n), xi(n), te(n), tx(n);
  const std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(n), 3, 3};
  py::array_t<double> lgu(shape), ins(shape);
  double *lgu_out = lgu.mutable_data(), *ins_out = ins.mutable_data();
  for (std::size_t k = 0; k < n; ++k) {
    const md::Sample& s = samples[k];
    t[k] = s.time_s;
    lat[k] = units::rad_to_deg(s.lat_rad);
    lon[k] = units::rad_to_deg(s.lon_rad);
    h[k] = s.height_m;
    v[k] = s.speed_m_s;
    eta[k] = rad_to_arcsec(s.model_eta_rad);
    xi[k] = rad_to_arcsec(s.model_xi_rad);
    if (has_truth) {
      te[k] = rad_to_arcsec(truth[k].eta_rad);
      tx[k] = rad_to_arcsec(truth[k].xi_rad);
    }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        lgu_out[9 * k + 3 * i + j] = s.lgu_body_to_nav(i, j);
        ins_out[9 * k + 3 * i + j] = s.ins_body_to_nav(i, j);
      }
  }
  py::dict d;
  d["time_s"] = to_numpy(t);
  d["lat_deg"] = to_numpy(lat);
  d["lon_deg"] = to_numpy(lon);
  d["height_m"] = to_numpy(h);
  d["speed_m_s"] = to_numpy(v);
  d["lgu_body_to_nav"] = lgu;
  d["ins_body_to_nav"] = ins;
  if (model) {
    d["model_eta_arcsec"] = to_numpy(eta);
    d["model_xi_arcsec"] = to_numpy(xi);
  }
  if (has_truth) {
    d["truth_eta_arcsec"] = to_numpy(te);
    d["truth_xi_arcsec"] = to_numpy(tx);
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
  md::Input in;
  {
    py::gil_scoped_release released;
    in = md::simulate(so);
  }
  return line_columns(in.samples, in.truth, true);
}

// A line file (CSV or binary, by content) read whole, as the columns simulate() gives: the
// model columns only when the file has them, the truth columns only when it has them.
// Also the header's columns the reader does not use (a misspelt optional column), for a warning.
py::tuple read_line(const std::string& path) {
  io::DovLine line;
  {
    py::gil_scoped_release released;
    line = io::read_dov_line_file(path);
  }
  return py::make_tuple(line_columns(line.samples, line.truth, line.has_model_values),
                        line.ignored_columns);
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
