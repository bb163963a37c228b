// meridian._core.maglev: the maglev gyro workflows as `meridian maglev` runs them, through the
// same runners (io/maglev_jobs.hpp) and writers (report/maglev_json.hpp) as the CLI
// (apps/meridian/cmd_maglev.cpp): a two-position reduction from arrays or files, wavelet
// denoising, the multi-angle calibration and the simulator. Reductions and calibrations return
// the CLI's --json text and the per-sample arrays; python/meridian/maglev.py gives them their
// Python face. The options arrive as one dict of every key (maglev.py fills the defaults);
// angles in degrees and arc-seconds, converted here.

#include <pybind11/stl.h>

#include <algorithm>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "meridian/core/units.hpp"
#include "meridian/io/maglev_jobs.hpp"
#include "meridian/maglev/calibration.hpp"
#include "meridian/maglev/denoise.hpp"
#include "meridian/maglev/reduce.hpp"
#include "meridian/maglev/simulator.hpp"
#include "meridian/report/json_text.hpp"
#include "meridian/report/maglev_json.hpp"

namespace py = pybind11;

namespace meridian::python {
namespace {

namespace mm = meridian::maglev;

ErrorContext argument(const char* name) { return {"", std::nullopt, name}; }

template <class T>
std::optional<T> optional_of(const py::dict& o, const char* key) {
  const py::object v = o[key];
  if (v.is_none()) return std::nullopt;
  return v.cast<T>();
}

mm::DenoiseOptions denoise_options(const py::dict& o) {
  mm::DenoiseOptions d;
  d.wavelet_order = mm::Wavelet::from_name(o["wavelet"].cast<std::string>()).order();
  d.level = o["level"].cast<int>();
  d.mode = mm::extension_mode_from_string(o["mode"].cast<std::string>());
  d.kind = mm::threshold_kind_from_string(o["threshold"].cast<std::string>());
  d.rule = mm::threshold_rule_from_string(o["rule"].cast<std::string>());
  return d;
}

// The azimuth chain of the keyword arguments (target_deg given).
mm::ChainSetup chain_setup(double target_deg, const py::dict& o) {
  mm::ChainSetup c;
  c.target_reading_rad = {units::deg_to_rad(target_deg),
                          units::arcsec_to_rad(o["target_sigma_arcsec"].cast<double>())};
  c.instrument_constant_rad = {
      units::deg_to_rad(o["instrument_constant_deg"].cast<double>()),
      units::arcsec_to_rad(o["instrument_constant_sigma_arcsec"].cast<double>())};
  if (const auto eta = optional_of<double>(o, "eta_arcsec"))
    c.eta_rad = Uncertain{units::arcsec_to_rad(*eta),
                          units::arcsec_to_rad(o["eta_sigma_arcsec"].cast<double>())};
  c.convergence_rad = units::deg_to_rad(o["convergence_deg"].cast<double>());
  return c;
}

// The keyword arguments of reduce() and reduce_files() as the runner takes them: they win over
// the constants of the files, as the CLI's options do.
io::MaglevReduceSetup reduce_setup(const py::dict& o, std::string config = {},
                                   std::string calibration = {}) {
  io::MaglevReduceSetup s;
  s.constants_file = std::move(config);
  s.calibration_file = std::move(calibration);
  if (const auto k = optional_of<double>(o, "scale_A_s_per_rad"))
    s.given.scale_A_s_per_rad = Uncertain{*k, o["scale_sigma_A_s_per_rad"].cast<double>()};
  if (const auto lat = optional_of<double>(o, "latitude_deg"))
    s.given.latitude_rad = units::deg_to_rad(*lat);
  if (const auto r1 = optional_of<double>(o, "reading1_deg"))
    s.given.circle_reading1_rad = units::deg_to_rad(*r1);
  if (const auto b = optional_of<double>(o, "prior_bias_A"))
    s.given.constant_deviation_A = Uncertain{*b, o["prior_bias_sigma_A"].cast<double>()};
  s.reading1_sigma_rad = units::arcsec_to_rad(o["reading1_sigma_arcsec"].cast<double>());
  if (const auto target = optional_of<double>(o, "target_deg")) s.chain = chain_setup(*target, o);
  s.options.process = o["process"].cast<bool>();
  s.options.denoise = o["denoise"].cast<bool>();
  s.options.stationarity.segment_length = o["segment"].cast<std::size_t>();
  s.options.stationarity.alpha = o["alpha"].cast<double>();
  s.options.stationarity.autocovariance_lags = o["lags"].cast<int>();
  s.options.denoising = denoise_options(o);
  s.options.drift = mm::drift_model_from_string(o["drift"].cast<std::string>());
  s.names = {"scale_A_s_per_rad", "latitude_deg", "config", "calibration"};
  return s;
}

// (JSON text, {time_s, current_A, cleaned_A, kept} per position).
py::tuple reduce_output(const mm::ReduceResult& r) {
  auto series = [](const mm::PositionResult& p) {
    py::array_t<bool> kept(static_cast<py::ssize_t>(p.kept_mask.size()));
    std::transform(p.kept_mask.begin(), p.kept_mask.end(), kept.mutable_data(),
                   [](char c) { return c != 0; });
    py::dict d;
    d["time_s"] = to_numpy(p.series.time_s);
    d["current_A"] = to_numpy(p.series.current_A);
    d["cleaned_A"] = to_numpy(p.cleaned_A);
    d["kept"] = kept;
    return d;
  };
  return py::make_tuple(report::json_compact(report::maglev_reduce_to_json(r)), series(r.position1),
                        series(r.position2));
}

py::tuple reduce_arrays(const Array& t1, const Array& c1, const Array& t2, const Array& c2,
                        const py::dict& o) {
  const io::MaglevReduceSetup setup = reduce_setup(o);
  // One statement each: GCC 12 destroys a partly built aggregate twice when a later member throws.
  mm::PositionSeries p1, p2;
  p1.time_s = to_vector(t1, "position1.time_s");
  p1.current_A = to_vector(c1, "position1.current_A");
  p2.time_s = to_vector(t2, "position2.time_s");
  p2.current_A = to_vector(c2, "position2.current_A");
  mm::ReduceResult r;
  {
    py::gil_scoped_release released;
    r = io::run_maglev_reduce(setup, std::move(p1), std::move(p2));
  }
  return reduce_output(r);
}

py::tuple reduce_files(const std::vector<std::string>& files, const std::string& config,
                       const std::string& calibration, const py::dict& o) {
  const io::MaglevReduceSetup setup = reduce_setup(o, config, calibration);
  mm::ReduceResult r;
  {
    py::gil_scoped_release released;
    r = io::run_maglev_reduce_files(files, setup);
  }
  return reduce_output(r);
}

// (values, noise_sigma, thresholds, zeroed, coefficients, level used). A level of 0 is
// `maglev denoise`'s default: 6, lowered to what the series allows.
py::tuple denoise(const Array& x, const py::dict& o) {
  const std::vector<double> v = to_vector(x, "series");
  mm::DenoiseOptions d = denoise_options(o);
  mm::DenoiseResult r;
  {
    py::gil_scoped_release released;
    if (d.level == 0) d.level = mm::default_level(v.size(), mm::Wavelet(d.wavelet_order));
    try {
      r = mm::denoise(v, d);
    } catch (Error& e) {
      if (e.context().field.empty()) e.add_context("", std::nullopt, "series");
      throw;
    }
  }
  return py::make_tuple(to_numpy(r.values), r.noise_sigma, r.thresholds, r.zeroed, r.coefficients,
                        r.options.level);
}

std::string calibrate_arrays(const Array& az_deg, const Array& m1, const Array& s1, const Array& m2,
                             const Array& s2, double latitude_deg, double alpha,
                             std::optional<double> nominal) {
  const std::vector<double> a = to_vector(az_deg, "azimuth_deg"), x1 = to_vector(m1, "mean1_A"),
                            y1 = to_vector(s1, "sigma1_A"), x2 = to_vector(m2, "mean2_A"),
                            y2 = to_vector(s2, "sigma2_A");
  for (const auto* v : {&x1, &y1, &x2, &y2})
    if (v->size() != a.size())
      throw InputError("azimuth_deg, mean1_A, sigma1_A, mean2_A and sigma2_A must have one length",
                       argument("table"));
  mm::CalibrationInput in;
  for (std::size_t j = 0; j < a.size(); ++j)
    in.setups.push_back({units::deg_to_rad(a[j]), {x1[j], y1[j]}, {x2[j], y2[j]}});
  in.latitude_rad = units::deg_to_rad(latitude_deg);
  in.alpha = alpha;
  in.nominal_scale_A_s_per_rad = nominal;
  py::gil_scoped_release released;
  return report::json_compact(report::maglev_calibration_to_json(mm::calibrate(in)));
}

std::string calibrate_file(const std::string& path, double latitude_deg, double alpha,
                           std::optional<double> nominal) {
  py::gil_scoped_release released;
  return report::json_compact(report::maglev_calibration_to_json(
      io::run_maglev_calibrate_file(path, units::deg_to_rad(latitude_deg), alpha, nominal)));
}

mm::NoiseSpec noise_spec(const py::dict& o) {
  mm::NoiseSpec s;
  s.samples = o["samples"].cast<std::size_t>();
  s.rate_hz = o["rate_hz"].cast<double>();
  s.white_sigma_A = o["white_A"].cast<double>();
  s.ar1_phi = o["ar1_phi"].cast<double>();
  s.ar1_sigma_A = o["ar1_sigma_A"].cast<double>();
  s.drift_A_per_s = o["drift_A_per_s"].cast<double>();
  return s;
}

// A calibration table as calibrate()'s columns: azimuth_deg, mean1_A, sigma1_A, mean2_A, sigma2_A.
py::dict calibration_columns(const mm::CalibrationInput& in) {
  using Column = double (*)(const mm::CalibrationSetup&);
  const std::pair<const char*, Column> columns[] = {
      {"azimuth_deg", [](const mm::CalibrationSetup& s) { return units::rad_to_deg(s.azimuth_rad); }},
      {"mean1_A", [](const mm::CalibrationSetup& s) { return s.mean1_A.value; }},
      {"sigma1_A", [](const mm::CalibrationSetup& s) { return s.mean1_A.sigma; }},
      {"mean2_A", [](const mm::CalibrationSetup& s) { return s.mean2_A.value; }},
      {"sigma2_A", [](const mm::CalibrationSetup& s) { return s.mean2_A.sigma; }}};
  py::dict d;
  for (const auto& [name, value] : columns) {
    std::vector<double> v;
    for (const auto& s : in.setups) v.push_back(value(s));
    d[name] = to_numpy(v);
  }
  return d;
}

py::dict series_dict(const mm::PositionSeries& s) {
  py::dict d;
  d["time_s"] = to_numpy(s.time_s);
  d["current_A"] = to_numpy(s.current_A);
  return d;
}

py::tuple simulate(const py::dict& truth, const py::dict& noise,
                   const std::vector<std::vector<double>>& bursts, std::uint64_t seed) {
  mm::DeterminationSimulation sim;
  sim.truth.alpha1_rad = units::deg_to_rad(truth["alpha1_deg"].cast<double>());
  sim.truth.scale_A_s_per_rad = truth["scale_A_s_per_rad"].cast<double>();
  sim.truth.bias_A = truth["bias_A"].cast<double>();
  sim.truth.latitude_rad = units::deg_to_rad(truth["latitude_deg"].cast<double>());
  sim.truth.circle_reading1_rad = units::deg_to_rad(truth["reading1_deg"].cast<double>());
  sim.noise = noise_spec(noise);
  for (const auto& b : bursts)
    sim.bursts.push_back({static_cast<int>(b.at(0)), {b.at(1), b.at(2), b.at(3), b.at(4), b.at(5), b.at(6)}});
  sim.seed = seed;
  mm::ReduceInput in;
  {
    py::gil_scoped_release released;
    in = mm::simulate_determination(sim);
  }
  return py::make_tuple(series_dict(in.position1), series_dict(in.position2));
}

py::dict simulate_calibration(const Array& azimuths_deg, const py::dict& truth,
                              const py::dict& noise, std::uint64_t seed) {
  mm::CalibrationSimulation sim;
  for (double az : to_vector(azimuths_deg, "azimuths_deg"))
    sim.azimuths_rad.push_back(units::deg_to_rad(az));
  sim.scale_A_s_per_rad = truth["scale_A_s_per_rad"].cast<double>();
  sim.latitude_rad = units::deg_to_rad(truth["latitude_deg"].cast<double>());
  sim.slope_ratio1 = truth["slope_ratio1"].cast<double>();
  sim.slope_ratio2 = truth["slope_ratio2"].cast<double>();
  sim.best_azimuth_rad = units::deg_to_rad(truth["best_azimuth_deg"].cast<double>());
  sim.constant_deviation_A = truth["constant_deviation_A"].cast<double>();
  sim.noise = noise_spec(noise);
  sim.seed = seed;
  mm::CalibrationInput in;
  {
    py::gil_scoped_release released;
    in = mm::simulate_calibration(sim);
  }
  return calibration_columns(in);
}

}  // namespace

void bind_maglev(py::module_& m) {
  m.def("reduce_arrays", &reduce_arrays, py::arg("time1_s"), py::arg("current1_A"),
        py::arg("time2_s"), py::arg("current2_A"), py::arg("options"),
        "`maglev reduce --json` on arrays: (JSON text, series 1, series 2)");
  m.def("reduce_files", &reduce_files, py::arg("files"), py::arg("config"), py::arg("calibration"),
        py::arg("options"), "`maglev reduce FILE [FILE2] --json`: (JSON text, series 1, series 2)");
  m.def("denoise", &denoise, py::arg("series"), py::arg("options"),
        "(values, noise_sigma, thresholds, zeroed, coefficients, level) of maglev::denoise");
  m.def("calibrate_arrays", &calibrate_arrays, py::arg("azimuth_deg"), py::arg("mean1_A"),
        py::arg("sigma1_A"), py::arg("mean2_A"), py::arg("sigma2_A"), py::arg("latitude_deg"),
        py::arg("alpha"), py::arg("nominal_scale_A_s_per_rad"),
        "`maglev calibrate --json` on arrays");
  m.def("calibrate_file", &calibrate_file, py::arg("path"), py::arg("latitude_deg"),
        py::arg("alpha"), py::arg("nominal_scale_A_s_per_rad"), "`maglev calibrate TABLE --json`");
  m.def("simulate", &simulate, py::arg("truth"), py::arg("noise"), py::arg("bursts"),
        py::arg("seed"), "`maglev simulate`: the two positions' series");
  m.def("simulate_calibration", &simulate_calibration, py::arg("azimuths_deg"), py::arg("truth"),
        py::arg("noise"), py::arg("seed"),
        "`maglev simulate --calibration-azimuths`: the table's columns");
}

}  // namespace meridian::python
