// meridian maglev reduce | denoise | simulate | calibrate

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "cli_support.hpp"
#include "commands.hpp"
#include "meridian/core/dms.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/io/maglev_files.hpp"
#include "meridian/maglev/calibration.hpp"
#include "meridian/maglev/denoise.hpp"
#include "meridian/maglev/reduce.hpp"
#include "meridian/maglev/simulator.hpp"
#include "meridian/report/html.hpp"
#include "meridian/report/maglev_html.hpp"
#include "meridian/report/maglev_json.hpp"
#include "meridian/report/maglev_text.hpp"

namespace meridian::cli {
namespace maglev_cmd {
namespace {

ErrorContext option(const char* name) { return ErrorContext{"", std::nullopt, name}; }

struct DenoiseArgs {
  std::string wavelet = "db4", mode = "symmetric", threshold = "soft", rule = "universal";
  int level = 6;
  maglev::DenoiseOptions options() const {
    maglev::DenoiseOptions o;
    o.wavelet_order = maglev::Wavelet::from_name(wavelet).order();
    o.level = level;
    o.mode = maglev::extension_mode_from_string(mode);
    o.kind = maglev::threshold_kind_from_string(threshold);
    o.rule = maglev::threshold_rule_from_string(rule);
    return o;
  }
};

// Invalid option values are command-line errors (exit 2, as a missing option), checked by CLI11
// before anything runs.
const CLI::Validator kWaveletName =
    CLI::IsMember({"db2", "db3", "db4", "db5", "db6", "db7", "db8", "db9", "db10"});

CLI::Validator open_unit_interval() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0' || !(v > 0.0 && v < 1.0))
          return fmt::format("{} is not in (0, 1)", text);
        return {};
      },
      "in (0, 1)");
}

void add_denoise_options(CLI::App* c, DenoiseArgs& d) {
  c->add_option("--wavelet", d.wavelet, "Daubechies wavelet db2 … db10")
      ->check(kWaveletName)
      ->capture_default_str();
  c->add_option("--level", d.level, "Decomposition levels p")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  c->add_option("--mode", d.mode, "Signal extension: symmetric | periodization")
      ->check(CLI::IsMember({"symmetric", "periodization"}))
      ->capture_default_str();
  c->add_option("--threshold", d.threshold, "soft | hard")
      ->check(CLI::IsMember({"soft", "hard"}))
      ->capture_default_str();
  c->add_option("--rule", d.rule, "universal (sigma*sqrt(2 ln n)) | sure")
      ->check(CLI::IsMember({"universal", "sure"}))
      ->capture_default_str();
}

struct ReduceArgs {
  std::string file1, file2;
  std::vector<std::string> files;
  std::string config, calibration, latitude, reading1, target, instrument_constant = "0";
  std::optional<double> scale, prior_bias;
  double scale_sigma = 0, reading1_sigma_arcsec = 0, target_sigma_arcsec = 0,
         constant_sigma_arcsec = 0;
  double prior_bias_sigma = 0, convergence_deg = 0;
  std::optional<double> eta_arcsec;
  double eta_sigma_arcsec = 0;
  bool no_process = false, no_denoise = false, json = false, quiet = false;
  std::string report;
  std::size_t segment = 0;
  double alpha = 0.05;
  int lags = 10;
  DenoiseArgs d;
  std::string output;
};

int run_reduce(const ReduceArgs& a) {
  require_html_reports_for(a.report);
  maglev::ReduceInput in;
  io::MaglevConstants k;
  if (!a.config.empty()) k = io::read_maglev_constants(a.config);
  if (!a.calibration.empty()) {
    const auto c = io::read_maglev_constants(a.calibration);
    if (c.scale_A_s_per_rad) k.scale_A_s_per_rad = c.scale_A_s_per_rad;
    if (c.constant_deviation_A) k.constant_deviation_A = c.constant_deviation_A;
  }
  if (a.scale) k.scale_A_s_per_rad = Uncertain{*a.scale, a.scale_sigma};
  if (!a.latitude.empty()) k.latitude_rad = angle_option(a.latitude, "--latitude");
  if (!a.reading1.empty()) k.circle_reading1_rad = angle_option(a.reading1, "--reading1");
  if (!k.scale_A_s_per_rad)
    throw InputError("the scale K is needed: --scale, --config or --calibration",
                     option("--scale"));
  if (!k.latitude_rad)
    throw InputError("the latitude is needed: --latitude or --config", option("--latitude"));
  in.scale_A_s_per_rad = *k.scale_A_s_per_rad;
  in.latitude_rad = *k.latitude_rad;
  in.circle_reading1_rad = {k.circle_reading1_rad.value_or(0.0),
                            units::arcsec_to_rad(a.reading1_sigma_arcsec)};
  if (a.prior_bias) k.constant_deviation_A = Uncertain{*a.prior_bias, a.prior_bias_sigma};
  in.options.prior_bias_A = k.constant_deviation_A;
  in.options.process = !a.no_process;
  in.options.denoise = !a.no_denoise;
  in.options.stationarity.segment_length = a.segment;
  in.options.stationarity.alpha = a.alpha;
  in.options.stationarity.autocovariance_lags = a.lags;
  in.options.denoising = a.d.options();
  if (!a.target.empty()) {
    maglev::ChainSetup c;
    c.target_reading_rad = {angle_option(a.target, "--target"),
                            units::arcsec_to_rad(a.target_sigma_arcsec)};
    c.instrument_constant_rad = {angle_option(a.instrument_constant, "--instrument-constant"),
                                 units::arcsec_to_rad(a.constant_sigma_arcsec)};
    if (a.eta_arcsec)
      c.eta_rad =
          Uncertain{units::arcsec_to_rad(*a.eta_arcsec), units::arcsec_to_rad(a.eta_sigma_arcsec)};
    c.convergence_rad = units::deg_to_rad(a.convergence_deg);
    in.chain = c;
  }
  io::MaglevSeriesFile f1, f2;
  if (a.files.size() == 1) {
    auto p = io::read_maglev_two_positions(a.files[0]);
    f1 = std::move(p.first);
    f2 = std::move(p.second);
  } else if (a.files.size() == 2) {
    f1 = io::read_maglev_series_file(a.files[0], 1);
    f2 = io::read_maglev_series_file(a.files[1], 2);
  } else {
    throw InputError("give one file with a position column, or two files (position 1, position 2)",
                     option("FILES"));
  }
  in.position1 = f1.series;
  in.position2 = f2.series;
  TerminalProgress progress(a.quiet);
  const auto r = io::run_maglev_reduce(in, f1, f2, &progress);
  progress.finish();
  std::string input = a.files[0];
  if (a.files.size() == 2) input += ", " + a.files[1];
  // Everything is computed before anything is written.
  const std::string html = a.report.empty()
                               ? std::string()
                               : report::render_html(report::maglev_reduce_document(r, in, input));
  const std::string out = a.json ? report::maglev_reduce_to_json(r, in).dump(2) + "\n"
                                 : report::maglev_reduce_text(r);
  if (a.report.empty())
    emit(a.output, out);
  else
    emit_all({{a.output.empty() ? kStandardOutput : a.output, out}, {a.report, html}});
  return kOk;
}

struct DenoiseCmdArgs {
  std::string file, output;
  DenoiseArgs d;
  bool level_given = false;
};

int run_denoise(const DenoiseCmdArgs& a) {
  const auto f = io::read_maglev_series_file(a.file, 0);
  auto opts = a.d.options();
  // The default level 6 is lowered to what a short series allows (as reduce does); an explicit
  // --level is taken as asked and refused when too deep.
  if (!a.level_given)
    opts.level = std::max(
        1, std::min(opts.level, maglev::max_level(f.series.current_A.size(),
                                                  maglev::Wavelet(opts.wavelet_order))));
  maglev::DenoiseResult r;
  try {
    maglev::validate_series(f.series, "series");
    r = maglev::denoise(f.series.current_A, opts);
  } catch (Error& e) {
    e.add_context(f.file);
    throw;
  }
  maglev::PositionSeries out{f.series.time_s, r.values};
  std::string thresholds;
  for (double l : r.thresholds) thresholds += fmt::format(" {:.6g}", l);
  const std::string header = fmt::format(
      "meridian maglev denoise: {} levels {}, mode {}, {} {} threshold\nnoise sigma {:.6g} A; "
      "thresholds (level 1 "
      "first):{}",
      maglev::Wavelet(opts.wavelet_order).name(), opts.level, maglev::to_string(opts.mode),
      maglev::to_string(opts.rule), maglev::to_string(opts.kind), r.noise_sigma, thresholds);
  emit(a.output, io::maglev_series_csv(out, header));
  return kOk;
}

struct SimulateArgs {
  std::string alpha1 = "0.5", latitude = "35", reading1 = "0", out = "maglev";
  double scale = 8000, bias = 2e-4;
  maglev::NoiseSpec noise;
  std::vector<std::string> bursts;
  std::uint64_t seed = 1;
  bool one_file = false;
  std::vector<std::string> calibration_azimuths;
  double slope_ratio1 = 1.0, slope_ratio2 = 1.0, constant_deviation = 0.0;
  std::string best_azimuth = "0";
};

maglev::Burst parse_burst(const std::string& text, int& position) {
  // position:begin_s:end_s:amplitude_A:offset_A:f0_hz:f1_hz
  std::vector<double> v;
  std::size_t b = 0;
  while (b <= text.size()) {
    std::size_t e = text.find(':', b);
    if (e == std::string::npos) e = text.size();
    const std::string part = text.substr(b, e - b);
    char* end = nullptr;
    const double x = std::strtod(part.c_str(), &end);
    if (part.empty() || *end != '\0' || !std::isfinite(x))
      throw InputError(fmt::format("\"{}\" is not a number in burst \"{}\"", part, text),
                       option("--burst"));
    v.push_back(x);
    b = e + 1;
  }
  if (v.size() != 7 || (v[0] != 1 && v[0] != 2))
    throw InputError(
        fmt::format(
            "burst \"{}\": expected position:begin_s:end_s:amplitude_A:offset_A:f0_hz:f1_hz "
            "with position 1 or 2",
            text),
        option("--burst"));
  position = static_cast<int>(v[0]);
  return {v[1], v[2], v[3], v[4], v[5], v[6]};
}

int run_simulate(const SimulateArgs& a, const std::string& command) {
  const double lat = angle_option(a.latitude, "--latitude");
  if (!a.calibration_azimuths.empty()) {
    maglev::CalibrationTruth t;
    for (const auto& s : a.calibration_azimuths)
      t.azimuths_rad.push_back(angle_option(s, "--calibration-azimuths"));
    const double A = a.scale * units::kEarthRotationRate_rad_s * std::cos(lat);
    t.slope1_A = A * a.slope_ratio1;
    t.slope2_A = -A * a.slope_ratio2;
    t.best_azimuth_rad = angle_option(a.best_azimuth, "--best-azimuth");
    t.constant_deviation_A = a.constant_deviation;
    t.latitude_rad = lat;
    const auto in = maglev::simulate_calibration(t, a.noise, a.seed);
    emit(a.out + "-calibration.csv", io::maglev_calibration_csv(in, "made by: " + command));
    return kOk;
  }
  maglev::TwoPositionTruth t;
  t.alpha1_rad = angle_option(a.alpha1, "--alpha1");
  t.scale_A_s_per_rad = a.scale;
  t.bias_A = a.bias;
  t.latitude_rad = lat;
  t.circle_reading1_rad = angle_option(a.reading1, "--reading1");
  maglev::NoiseSpec s1 = a.noise, s2 = a.noise;
  s2.start_s = a.noise.start_s + static_cast<double>(a.noise.samples) / a.noise.rate_hz + 30.0;
  for (const auto& b : a.bursts) {
    int pos = 1;
    maglev::Burst burst = parse_burst(b, pos);
    // Burst times count from the start of their position's series.
    maglev::NoiseSpec& s = pos == 1 ? s1 : s2;
    burst.begin_s += s.start_s;
    burst.end_s += s.start_s;
    s.bursts.push_back(burst);
  }
  const auto in = maglev::simulate_determination(t, s1, s2, a.seed);
  const std::string header = fmt::format(
      "made by: {}\ntruth: alpha1 {:.6f} deg, K {} A*s/rad, b {} A, latitude {:.6f} deg, r1 {:.6f} "
      "deg",
      command, units::rad_to_deg(t.alpha1_rad), t.scale_A_s_per_rad, t.bias_A,
      units::rad_to_deg(lat), units::rad_to_deg(t.circle_reading1_rad));
  if (a.one_file) {
    emit(a.out + ".csv", io::maglev_two_position_csv(in.position1, in.position2, header));
  } else {
    const std::string p1 = io::maglev_series_csv(in.position1, header + "\nposition 1");
    const std::string p2 = io::maglev_series_csv(in.position2, header + "\nposition 2");
    emit(a.out + "-1.csv", p1);
    emit(a.out + "-2.csv", p2);
  }
  return kOk;
}

struct CalibrateArgs {
  std::string file, latitude, output, report;
  std::optional<double> nominal_scale;
  double alpha = 0.05;
  bool json = false;
};

int run_calibrate(const CalibrateArgs& a) {
  require_html_reports_for(a.report);
  auto in = io::read_maglev_calibration_table(a.file);
  in.latitude_rad = angle_option(a.latitude, "--latitude");
  in.alpha = a.alpha;
  in.nominal_scale_A_s_per_rad = a.nominal_scale;
  maglev::CalibrationResult r;
  try {
    r = maglev::calibrate(in);
  } catch (Error& e) {
    e.add_context(a.file);
    throw;
  }
  const std::string html =
      a.report.empty() ? std::string()
                       : report::render_html(report::maglev_calibration_document(r, in, a.file));
  const std::string out = a.json ? report::maglev_calibration_to_json(r).dump(2) + "\n"
                                 : report::maglev_calibration_text(r);
  if (a.report.empty())
    emit(a.output, out);
  else
    emit_all({{a.output.empty() ? kStandardOutput : a.output, out}, {a.report, html}});
  return kOk;
}

}  // namespace
}  // namespace maglev_cmd

void add_maglev_commands(CLI::App& app, int& exit_code) {
  using namespace maglev_cmd;  // the command's option structs and run functions
  CLI::App* mg =
      app.add_subcommand("maglev", "Magnetically suspended gyro: two-position north seeking");
  mg->require_subcommand(1);

  auto ra = std::make_shared<ReduceArgs>();
  CLI::App* red =
      mg->add_subcommand("reduce", "Two-position determination from rotor-current series (CSV)");
  // Two positionals, so that the usage line reads FILE [FILE2].
  red->add_option("FILE", ra->file1,
                  "CSV of position 1, or one CSV with a position column for both")
      ->required();
  red->add_option("FILE2", ra->file2, "CSV of position 2 (when FILE holds position 1 only)");
  red->add_option("--config", ra->config,
                  "YAML/JSON with scale_A_s_per_rad, latitude, circle_reading1, ...");
  red->add_option("--calibration", ra->calibration,
                  "Stored calibration (maglev calibrate --json): K and the prior bias I*");
  red->add_option("--scale", ra->scale, "K, A*s/rad (current per unit horizontal earth rate)");
  red->add_option("--scale-sigma", ra->scale_sigma, "sigma of K, A*s/rad")->capture_default_str();
  red->add_option("--latitude", ra->latitude, "Station latitude (DMS or deg)");
  red->add_option("--reading1", ra->reading1,
                  "Circle reading r1 of the spin axis at position 1 (DMS or deg)");
  red->add_option("--reading1-sigma-arcsec", ra->reading1_sigma_arcsec, "sigma of r1")
      ->capture_default_str();
  red->add_option("--prior-bias", ra->prior_bias, "Prior bias b0 (A) for the symmetry check");
  red->add_option("--prior-bias-sigma", ra->prior_bias_sigma, "sigma of b0 (A)")
      ->capture_default_str();
  red->add_option("--target", ra->target, "Circle reading of the target: gives the azimuth chain");
  red->add_option("--target-sigma-arcsec", ra->target_sigma_arcsec, "sigma of the target reading")
      ->capture_default_str();
  red->add_option("--instrument-constant", ra->instrument_constant, "E (DMS or deg)")
      ->capture_default_str();
  red->add_option("--instrument-constant-sigma-arcsec", ra->constant_sigma_arcsec, "sigma of E")
      ->capture_default_str();
  red->add_option("--eta-arcsec", ra->eta_arcsec, "Prime-vertical deflection eta (Laplace)");
  red->add_option("--eta-sigma-arcsec", ra->eta_sigma_arcsec, "sigma of eta")
      ->capture_default_str();
  red->add_option("--convergence-deg", ra->convergence_deg, "Meridian convergence gamma (deg)")
      ->capture_default_str();
  red->add_flag("--no-process", ra->no_process,
                "Plain means of all samples (no tests, no denoising)");
  red->add_flag("--no-denoise", ra->no_denoise, "Stationarity tests without wavelet denoising");
  red->add_option("--segment", ra->segment,
                  "Segment length in samples, >= 32 (0: about 20 segments)")
      ->check(CLI::Validator(
          [](std::string& t) -> std::string {
            char* end = nullptr;
            const long v = std::strtol(t.c_str(), &end, 10);
            return !t.empty() && *end == '\0' && (v == 0 || v >= 32)
                       ? std::string()
                       : t + " is not 0 (automatic) or at least 32";
          },
          "0 or >= 32"))
      ->capture_default_str();
  red->add_option("--alpha", ra->alpha, "Significance level per position (family-wise)")
      ->check(open_unit_interval())
      ->capture_default_str();
  red->add_option("--lags", ra->lags, "Autocovariance lags M of the segment test")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  add_denoise_options(red, ra->d);
  red->add_flag("--json", ra->json, "Print JSON instead of text");
  red->add_option("-o,--output", ra->output, "Write to this file (atomically) instead of stdout");
  red->add_option("--report", ra->report,
                  "Also write a self-contained HTML report (series, segments) to this file");
  red->add_flag("-q,--quiet", ra->quiet, "No progress bar");
  red->callback([ra, &exit_code] {
    ra->files = {ra->file1};
    if (!ra->file2.empty()) ra->files.push_back(ra->file2);
    // K and φ may come from --config / --calibration; with neither file a missing option is a
    // command-line error (exit 2). A file that lacks them is a bad input (exit 1).
    if (!ra->scale && ra->config.empty() && ra->calibration.empty())
      throw CLI::RequiredError("--scale (or --config / --calibration giving K)");
    if (ra->latitude.empty() && ra->config.empty())
      throw CLI::RequiredError("--latitude (or --config giving latitude)");
    exit_code = guarded([&] { return run_reduce(*ra); });
  });

  auto da = std::make_shared<DenoiseCmdArgs>();
  CLI::App* den = mg->add_subcommand(
      "denoise",
      "Wavelet-denoise a series (time, current CSV; header units applied); writes "
      "`time [s],current [A]` CSV in SI units (default level 6, lowered for a short series)");
  den->add_option("CSV", da->file, "Input CSV (time, current); - for stdin")->required();
  add_denoise_options(den, da->d);
  den->add_option("-o,--output", da->output, "Write to this file (atomically) instead of stdout");
  den->callback([da, den, &exit_code] {
    da->level_given = den->get_option("--level")->count() > 0;
    exit_code = guarded([&] { return run_denoise(*da); });
  });

  auto sa = std::make_shared<SimulateArgs>();
  CLI::App* sim = mg->add_subcommand(
      "simulate", "Simulate a determination (CSV per position) or a calibration table");
  sim->add_option("--alpha1", sa->alpha1,
                  "True alpha1, spin axis east of north at position 1 (DMS or deg)")
      ->capture_default_str();
  sim->add_option("--scale", sa->scale, "K, A*s/rad")->capture_default_str();
  sim->add_option("--bias", sa->bias, "b, A")->capture_default_str();
  sim->add_option("--latitude", sa->latitude, "Latitude (DMS or deg)")->capture_default_str();
  sim->add_option("--reading1", sa->reading1, "r1 (DMS or deg)")->capture_default_str();
  sim->add_option("--samples", sa->noise.samples, "Samples per position")->capture_default_str();
  sim->add_option("--rate-hz", sa->noise.rate_hz, "Sample rate")->capture_default_str();
  sim->add_option("--white", sa->noise.white_sigma_A, "White noise sigma (A)")
      ->capture_default_str();
  sim->add_option("--ar1-phi", sa->noise.ar1_phi, "AR(1) coefficient")->capture_default_str();
  sim->add_option("--ar1-sigma", sa->noise.ar1_sigma_A, "AR(1) innovation sigma (A)")
      ->capture_default_str();
  sim->add_option("--drift", sa->noise.drift_A_per_s, "Drift (A/s)")->capture_default_str();
  sim->add_option(
      "--burst", sa->bursts,
      "Interference: position:begin_s:end_s:amplitude_A:offset_A:f0_hz:f1_hz, times from the start of that position's series (repeatable)");
  sim->add_option("--seed", sa->seed, "Random seed")->capture_default_str();
  sim->add_flag("--one-file", sa->one_file,
                "Write OUT.csv with a position column instead of OUT-1.csv, OUT-2.csv");
  sim->add_option(
         "--calibration-azimuths", sa->calibration_azimuths,
         "Simulate a calibration table (OUT-calibration.csv) at these set-up azimuths (DMS or deg)")
      ->delimiter(',');
  sim->add_option("--slope-ratio1", sa->slope_ratio1, "Calibration: k1 = ratio*K*w*cos(phi)")
      ->capture_default_str();
  sim->add_option("--slope-ratio2", sa->slope_ratio2, "Calibration: k2 = -ratio*K*w*cos(phi)")
      ->capture_default_str();
  sim->add_option("--best-azimuth", sa->best_azimuth, "Calibration: alpha* where the lines meet")
      ->capture_default_str();
  sim->add_option("--constant-deviation", sa->constant_deviation, "Calibration: I* (A)")
      ->capture_default_str();
  sim->add_option("--out", sa->out, "Output prefix")->capture_default_str();
  sim->callback([sa, sim, &exit_code] {
    std::string cmd = "meridian maglev simulate";
    for (const CLI::Option* o : sim->get_options()) {
      if (o->count() == 0 || o->get_lnames().empty()) continue;
      const std::string name = o->get_lnames().front();
      if (name == "help" || name == "out") continue;
      cmd += " --" + name;
      if (o->get_expected_min() == 0) continue;
      std::string value;
      for (const auto& r : o->results()) value += (value.empty() ? "" : ",") + r;
      if (o->get_lnames().front() == "burst")
        value = fmt::format("{}", fmt::join(o->results(), " --burst="));
      cmd += "=" + value;
    }
    exit_code = guarded([&] { return run_simulate(*sa, cmd); });
  });

  auto ca = std::make_shared<CalibrateArgs>();
  CLI::App* cal = mg->add_subcommand(
      "calibrate", "Multi-angle calibration: lines, trend deviation, alpha*, I*, K");
  cal->add_option("TABLE", ca->file, "CSV: azimuth, mean1, sigma1, mean2, sigma2")->required();
  cal->add_option("--latitude", ca->latitude, "Latitude (DMS or deg)")->required();
  cal->add_option("--nominal-scale", ca->nominal_scale,
                  "Nominal K to compare the slopes with (A*s/rad)");
  cal->add_option("--alpha", ca->alpha, "Significance level")
      ->check(open_unit_interval())
      ->capture_default_str();
  cal->add_flag("--json", ca->json,
                "Print JSON (also the stored calibration for reduce --calibration)");
  cal->add_option("-o,--output", ca->output, "Write to this file (atomically) instead of stdout");
  cal->add_option("--report", ca->report,
                  "Also write a self-contained HTML report (lines, residuals) to this file");
  cal->callback([ca, &exit_code] { exit_code = guarded([&] { return run_calibrate(*ca); }); });
}

}  // namespace meridian::cli
