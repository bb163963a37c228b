// meridian._core.maglev: the maglev gyro workflows as `meridian maglev` runs them
// (apps/meridian/cmd_maglev.cpp): a two-position reduction from arrays or files,
// wavelet denoising, the multi-angle calibration and the simulator. Reductions and
// calibrations return the CLI's --json text (report/maglev_json.hpp) and the
// per-sample arrays; python/meridian/maglev.py gives them their Python face. The
// options arrive as one dict of every key (maglev.py fills the defaults); angles in
// degrees and arc-seconds, converted here.

#include <pybind11/stl.h>

#include <algorithm>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "arrays.hpp"
#include "bindings.hpp"
#include "meridian/core/units.hpp"
#include "meridian/io/maglev_files.hpp"
#include "meridian/maglev/calibration.hpp"
#include "meridian/maglev/denoise.hpp"
#include "meridian/maglev/reduce.hpp"
#include "meridian/maglev/simulator.hpp"
#include "meridian/report/maglev_json.hpp"

namespace py = pybind11;

namespace meridian::python {
namespace {

namespace mm = meridian::maglev;

std::string json_text(const nlohmann::json& j) {
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

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

// The ReduceInput of `maglev reduce`: constants `k` (from --config/--calibration files)
// overridden by the keyword arguments in `o`, as the CLI's options override its files.
mm::ReduceInput reduce_input(io::MaglevConstants k, const py::dict& o) {
  if (const auto s = optional_of<double>(o, "scale_A_s_per_rad"))
    k.scale_A_s_per_rad = Uncertain{*s, o["scale_sigma_A_s_per_rad"].cast<double>()};
  if (const auto lat = optional_of<double>(o, "latitude_deg"))
    k.latitude_rad = units::deg_to_rad(*lat);
  if (const auto r1 = optional_of<double>(o, "reading1_deg"))
    k.circle_reading1_rad = units::deg_to_rad(*r1);
  if (!k.scale_A_s_per_rad)
    throw InputError("the scale K is needed: scale_A_s_per_rad, config or calibration",
                     argument("scale_A_s_per_rad"));
  if (!k.latitude_rad)
    throw InputError("the latitude is needed: latitude_deg or config", argument("latitude_deg"));
  mm::ReduceInput in;
  in.scale_A_s_per_rad = *k.scale_A_s_per_rad;
  in.latitude_rad = *k.latitude_rad;
  in.circle_reading1_rad = {k.circle_reading1_rad.value_or(0.0),
                            units::arcsec_to_rad(o["reading1_sigma_arcsec"].cast<double>())};
  if (const auto b = optional_of<double>(o, "prior_bias_A"))
    k.constant_deviation_A = Uncertain{*b, o["prior_bias_sigma_A"].cast<double>()};
  in.options.prior_bias_A = k.constant_deviation_A;
  in.options.process = o["process"].cast<bool>();
  in.options.denoise = o["denoise"].cast<bool>();
  in.options.stationarity.segment_length = o["segment"].cast<std::size_t>();
  in.options.stationarity.alpha = o["alpha"].cast<double>();
  in.options.stationarity.autocovariance_lags = o["lags"].cast<int>();
  in.options.denoising = denoise_options(o);
  if (const auto target = optional_of<double>(o, "target_deg")) {
    mm::ChainSetup c;
    c.target_reading_rad = {units::deg_to_rad(*target),
                            units::arcsec_to_rad(o["target_sigma_arcsec"].cast<double>())};
    c.instrument_constant_rad = {
        units::deg_to_rad(o["instrument_constant_deg"].cast<double>()),
        units::arcsec_to_rad(o["instrument_constant_sigma_arcsec"].cast<double>())};
    if (const auto eta = optional_of<double>(o, "eta_arcsec"))
      c.eta_rad = Uncertain{units::arcsec_to_rad(*eta),
                            units::arcsec_to_rad(o["eta_sigma_arcsec"].cast<double>())};
    c.convergence_rad = units::deg_to_rad(o["convergence_deg"].cast<double>());
    in.chain = c;
  }
  return in;
}

// (JSON text, {time_s, current_A, cleaned_A, kept} per position).
py::tuple reduce_output(const mm::ReduceResult& r, const mm::ReduceInput& in) {
  auto series = [](const mm::PositionSeries& s, const mm::PositionResult& p) {
    py::array_t<bool> kept(static_cast<py::ssize_t>(p.kept_mask.size()));
    std::transform(p.kept_mask.begin(), p.kept_mask.end(), kept.mutable_data(),
                   [](char c) { return c != 0; });
    py::dict d;
    d["time_s"] = to_numpy(s.time_s);
    d["current_A"] = to_numpy(s.current_A);
    d["cleaned_A"] = to_numpy(p.cleaned_A);
    d["kept"] = kept;
    return d;
  };
  return py::make_tuple(json_text(report::maglev_reduce_to_json(r, in)),
                        series(in.position1, r.position1), series(in.position2, r.position2));
}

py::tuple reduce_arrays(const Array& t1, const Array& c1, const Array& t2, const Array& c2,
                        const py::dict& o) {
  mm::ReduceInput in = reduce_input({}, o);
  in.position1 = {to_vector(t1, "position1.time_s"), to_vector(c1, "position1.current_A")};
  in.position2 = {to_vector(t2, "position2.time_s"), to_vector(c2, "position2.current_A")};
  mm::ReduceResult r;
  {
    py::gil_scoped_release released;
    r = mm::process(in);
  }
  return reduce_output(r, in);
}

py::tuple reduce_files(const std::vector<std::string>& files, const std::string& config,
                       const std::string& calibration, const py::dict& o) {
  io::MaglevConstants k;
  io::MaglevSeriesFile f1, f2;
  {
    py::gil_scoped_release released;
    if (!config.empty()) k = io::read_maglev_constants(config);
    if (!calibration.empty()) {
      const auto c = io::read_maglev_constants(calibration);
      if (c.scale_A_s_per_rad) k.scale_A_s_per_rad = c.scale_A_s_per_rad;
      if (c.constant_deviation_A) k.constant_deviation_A = c.constant_deviation_A;
    }
    if (files.size() == 1) {
      std::tie(f1, f2) = io::read_maglev_two_positions(files[0]);
    } else if (files.size() == 2) {
      f1 = io::read_maglev_series_file(files[0], 1);
      f2 = io::read_maglev_series_file(files[1], 2);
    } else {
      throw InputError(
          "give one file with a position column, or two files (position 1, position 2)",
          argument("files"));
    }
  }
  mm::ReduceInput in = reduce_input(k, o);
  in.position1 = f1.series;
  in.position2 = f2.series;
  mm::ReduceResult r;
  {
    py::gil_scoped_release released;
    r = io::run_maglev_reduce(in, f1, f2);
  }
  return reduce_output(r, in);
}

// (values, noise_sigma, thresholds, zeroed, coefficients, level used). A level of 0 is
// `maglev denoise`'s default: 6, lowered to what the series allows.
py::tuple denoise(const Array& x, const py::dict& o) {
  const std::vector<double> v = to_vector(x, "series");
  mm::DenoiseOptions d = denoise_options(o);
  mm::DenoiseResult r;
  {
    py::gil_scoped_release released;
    if (d.level == 0)
      d.level = std::max(1, std::min(6, mm::max_level(v.size(), mm::Wavelet(d.wavelet_order))));
    try {
      r = mm::denoise(v, d);
    } catch (Error& e) {
      if (e.context().field.empty()) e.add_context("", std::nullopt, "series");
      throw;
    }
  }
  return py::make_tuple(to_numpy(r.values), r.noise_sigma, r.thresholds, r.zeroed, r.coefficients,
                        d.level);
}

std::string calibrate(mm::CalibrationInput in, double latitude_deg, double alpha,
                      std::optional<double> nominal, const std::string& file) {
  py::gil_scoped_release released;
  in.latitude_rad = units::deg_to_rad(latitude_deg);
  in.alpha = alpha;
  in.nominal_scale_A_s_per_rad = nominal;
  try {
    return json_text(report::maglev_calibration_to_json(mm::calibrate(in)));
  } catch (Error& e) {
    if (!file.empty()) e.add_context(file);
    throw;
  }
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

py::dict series_dict(const mm::PositionSeries& s) {
  py::dict d;
  d["time_s"] = to_numpy(s.time_s);
  d["current_A"] = to_numpy(s.current_A);
  return d;
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
  m.def(
      "calibrate_arrays",
      [](const Array& az_deg, const Array& m1, const Array& s1, const Array& m2, const Array& s2,
         double latitude_deg, double alpha, std::optional<double> nominal) {
        const std::vector<double> a = to_vector(az_deg, "azimuth_deg"),
                                  x1 = to_vector(m1, "mean1_A"), y1 = to_vector(s1, "sigma1_A"),
                                  x2 = to_vector(m2, "mean2_A"), y2 = to_vector(s2, "sigma2_A");
        for (const auto* v : {&x1, &y1, &x2, &y2})
          if (v->size() != a.size())
            throw InputError(
                "azimuth_deg, mean1_A, sigma1_A, mean2_A and sigma2_A must have one length",
                argument("table"));
        mm::CalibrationInput in;
        for (std::size_t j = 0; j < a.size(); ++j)
          in.setups.push_back({units::deg_to_rad(a[j]), {x1[j], y1[j]}, {x2[j], y2[j]}});
        return calibrate(std::move(in), latitude_deg, alpha, nominal, "");
      },
      py::arg("azimuth_deg"), py::arg("mean1_A"), py::arg("sigma1_A"), py::arg("mean2_A"),
      py::arg("sigma2_A"), py::arg("latitude_deg"), py::arg("alpha"),
      py::arg("nominal_scale_A_s_per_rad"), "`maglev calibrate --json` on arrays");
  m.def(
      "calibrate_file",
      [](const std::string& path, double latitude_deg, double alpha,
         std::optional<double> nominal) {
        mm::CalibrationInput in;
        {
          py::gil_scoped_release released;
          in = io::read_maglev_calibration_table(path);
        }
        return calibrate(std::move(in), latitude_deg, alpha, nominal, path);
      },
      py::arg("path"), py::arg("latitude_deg"), py::arg("alpha"),
      py::arg("nominal_scale_A_s_per_rad"), "`maglev calibrate TABLE --json`");
  m.def(
      "simulate",
      [](const py::dict& truth, const py::dict& noise,
         const std::vector<std::vector<double>>& bursts, std::uint64_t seed) {
        mm::TwoPositionTruth t;
        t.alpha1_rad = units::deg_to_rad(truth["alpha1_deg"].cast<double>());
        t.scale_A_s_per_rad = truth["scale_A_s_per_rad"].cast<double>();
        t.bias_A = truth["bias_A"].cast<double>();
        t.latitude_rad = units::deg_to_rad(truth["latitude_deg"].cast<double>());
        t.circle_reading1_rad = units::deg_to_rad(truth["reading1_deg"].cast<double>());
        mm::NoiseSpec s1 = noise_spec(noise), s2 = s1;
        // As `maglev simulate`: position 2 starts 30 s after position 1 ends; burst times
        // count from the start of their position's series.
        s2.start_s = s1.start_s + static_cast<double>(s1.samples) / s1.rate_hz + 30.0;
        for (const auto& b : bursts) {
          mm::NoiseSpec& s = b.at(0) == 1 ? s1 : s2;
          s.bursts.push_back(
              {b.at(1) + s.start_s, b.at(2) + s.start_s, b.at(3), b.at(4), b.at(5), b.at(6)});
        }
        mm::ReduceInput in;
        {
          py::gil_scoped_release released;
          in = mm::simulate_determination(t, s1, s2, seed);
        }
        return py::make_tuple(series_dict(in.position1), series_dict(in.position2));
      },
      py::arg("truth"), py::arg("noise"), py::arg("bursts"), py::arg("seed"),
      "`maglev simulate`: the two positions' series");
  m.def(
      "simulate_calibration",
      [](const Array& azimuths_deg, const py::dict& truth, const py::dict& noise,
         std::uint64_t seed) {
        const double lat = units::deg_to_rad(truth["latitude_deg"].cast<double>());
        const double a = truth["scale_A_s_per_rad"].cast<double>() *
                         units::kEarthRotationRate_rad_s * std::cos(lat);
        mm::CalibrationTruth t;
        for (double az : to_vector(azimuths_deg, "azimuths_deg"))
          t.azimuths_rad.push_back(units::deg_to_rad(az));
        t.slope1_A = a * truth["slope_ratio1"].cast<double>();
        t.slope2_A = -a * truth["slope_ratio2"].cast<double>();
        t.best_azimuth_rad = units::deg_to_rad(truth["best_azimuth_deg"].cast<double>());
        t.constant_deviation_A = truth["constant_deviation_A"].cast<double>();
        t.latitude_rad = lat;
        const mm::NoiseSpec spec = noise_spec(noise);
        mm::CalibrationInput in;
        {
          py::gil_scoped_release released;
          in = mm::simulate_calibration(t, spec, seed);
        }
        std::vector<double> az, m1, s1, m2, s2;
        for (const auto& s : in.setups) {
          az.push_back(units::rad_to_deg(s.azimuth_rad));
          m1.push_back(s.mean1_A.value);
          s1.push_back(s.mean1_A.sigma);
          m2.push_back(s.mean2_A.value);
          s2.push_back(s.mean2_A.sigma);
        }
        py::dict d;
        d["azimuth_deg"] = to_numpy(az);
        d["mean1_A"] = to_numpy(m1);
        d["sigma1_A"] = to_numpy(s1);
        d["mean2_A"] = to_numpy(m2);
        d["sigma2_A"] = to_numpy(s2);
        return d;
      },
      py::arg("azimuths_deg"), py::arg("truth"), py::arg("noise"), py::arg("seed"),
      "`maglev simulate --calibration-azimuths`: the table's columns");
}

}  // namespace meridian::python
