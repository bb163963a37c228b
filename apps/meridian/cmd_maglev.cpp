// meridian maglev reduce | denoise | simulate | calibrate

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
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/io/maglev_files.hpp"
#include "meridian/io/maglev_jobs.hpp"
#include "meridian/maglev/simulator.hpp"
#include "meridian/report/html.hpp"
#include "meridian/report/json_text.hpp"
#include "meridian/report/maglev_html.hpp"
#include "meridian/report/maglev_json.hpp"
#include "meridian/report/maglev_text.hpp"

namespace meridian::cli {
namespace maglev_cmd {
namespace {

ErrorContext option(const char* name) { return ErrorContext{"", std::nullopt, name}; }

struct DenoiseArgs {
  std::string wavelet = "db4", mode = "symmetric", threshold = "soft", rule = "universal";
  int level = maglev::kDefaultLevel;
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

CLI::Validator segment_length() {
  return CLI::Validator(
      [](std::string& t) -> std::string {
        char* end = nullptr;
        const long v = std::strtol(t.c_str(), &end, 10);
        return !t.empty() && *end == '\0' && (v == 0 || v >= 32)
                   ? std::string()
                   : t + " is not 0 (automatic) or at least 32";
      },
      "0 or >= 32");
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
  std::string drift = "linear";
  std::optional<double> settling_cut;
  bool no_settling_detect = false;
  std::string report;
  std::size_t segment = 0;
  double alpha = 0.05;
  int lags = 10;
  DenoiseArgs d;
  std::string output;

  // --target and what goes with it: the azimuth chain.
  maglev::ChainSetup chain() const {
    maglev::ChainSetup c;
    c.target_reading_rad = {angle_option(target, "--target"),
                            units::arcsec_to_rad(target_sigma_arcsec)};
    c.instrument_constant_rad = {angle_option(instrument_constant, "--instrument-constant"),
                                 units::arcsec_to_rad(constant_sigma_arcsec)};
    if (eta_arcsec)
      c.eta_rad =
          Uncertain{units::arcsec_to_rad(*eta_arcsec), units::arcsec_to_rad(eta_sigma_arcsec)};
    c.convergence_rad = units::deg_to_rad(convergence_deg);
    return c;
  }

  // The options as the runner takes them: the files, the values that win over them, the
  // processing options.
  io::MaglevReduceSetup setup() const {
    io::MaglevReduceSetup s;
    s.constants_file = config;
    s.calibration_file = calibration;
    if (scale) s.given.scale_A_s_per_rad = Uncertain{*scale, scale_sigma};
    if (!latitude.empty()) s.given.latitude_rad = angle_option(latitude, "--latitude");
    if (!reading1.empty()) s.given.circle_reading1_rad = angle_option(reading1, "--reading1");
    if (prior_bias) s.given.constant_deviation_A = Uncertain{*prior_bias, prior_bias_sigma};
    s.reading1_sigma_rad = units::arcsec_to_rad(reading1_sigma_arcsec);
    if (!target.empty()) s.chain = chain();
    s.options.process = !no_process;
    s.options.denoise = !no_denoise;
    s.options.drift = maglev::drift_model_from_string(drift);
    s.options.settling.cut_s = settling_cut;
    s.options.settling.detect = !no_settling_detect;
    s.options.stationarity.segment_length = segment;
    s.options.stationarity.alpha = alpha;
    s.options.stationarity.autocovariance_lags = lags;
    s.options.denoising = d.options();
    s.names = {"--scale", "--latitude", "--config", "--calibration"};
    return s;
  }
};

int run_reduce(const ReduceArgs& a) {
  require_html_reports_for(a.report);
  std::vector<std::string> inputs = a.files;
  inputs.push_back(a.config);
  inputs.push_back(a.calibration);
  check_output_paths({{a.output, "-o", "output"}, {a.report, "--report", "report"}}, inputs);
  TerminalProgress progress(a.quiet);
  const maglev::ReduceResult r = io::run_maglev_reduce_files(a.files, a.setup(), &progress);
  progress.finish();
  // Everything is computed before anything is written.
  const std::string out = a.json ? report::json_text(report::maglev_reduce_to_json(r))
                                 : report::maglev_reduce_text(r);
  emit_with_report(a.output, out, a.report,
                   [&] { return report::render_html(report::maglev_reduce_document(r)); });
  return kOk;
}

struct DenoiseCmdArgs {
  std::string file, output;
  DenoiseArgs d;
  bool level_given = false;
};

int run_denoise(const DenoiseCmdArgs& a) {
  check_output_paths({{a.output, "-o", "output"}}, {a.file});
  maglev::DenoiseOptions options = a.d.options();
  // Level 0: the default, lowered to what a short series allows (as reduce does); an explicit
  // --level is taken as asked and refused when too deep.
  if (!a.level_given) options.level = 0;
  const maglev::SeriesDenoising r = io::run_maglev_denoise_file(a.file, options);
  emit(a.output, io::maglev_series_csv(r.series, report::maglev_denoise_text(r.denoising)));
  return kOk;
}

struct SimulateArgs {
  std::string alpha1 = "0.5", latitude = "35", reading1 = "0", out = "maglev";
  double scale = 8000, bias = 2e-4;
  maglev::NoiseSpec noise;
  std::vector<std::string> bursts, steps, sequence{"1", "2"};
  std::string settling;
  double pause = 30.0;
  bool drift_restarts = false;
  std::uint64_t seed = 1;
  bool one_file = false;
  std::vector<std::string> calibration_azimuths;
  double slope_ratio1 = 1.0, slope_ratio2 = 1.0, constant_deviation = 0.0;
  std::string best_azimuth = "0";

  maglev::DeterminationSimulation determination() const;
  maglev::CalibrationSimulation calibration() const;
};

// "a:b:c" → numbers, each finite; `label` names the text in the message ("burst " or empty).
std::vector<double> split_colon_numbers(const std::string& text, const char* what, const char* label) {
  std::vector<double> v;
  std::size_t b = 0;
  while (b <= text.size()) {
    std::size_t e = text.find(':', b);
    if (e == std::string::npos) e = text.size();
    const std::string part = text.substr(b, e - b);
    char* end = nullptr;
    const double x = std::strtod(part.c_str(), &end);
    if (part.empty() || *end != '\0' || !std::isfinite(x))
      throw InputError(fmt::format("\"{}\" is not a number in {}\"{}\"", part, label, text), option(what));
    v.push_back(x);
    b = e + 1;
  }
  return v;
}

// --burst position:begin_s:end_s:amplitude_A:offset_A:f0_hz:f1_hz
maglev::PositionBurst parse_burst(const std::string& text) {
  const std::vector<double> v = split_colon_numbers(text, "--burst", "burst ");
  if (v.size() != 7 || (v[0] != 1 && v[0] != 2))
    throw InputError(
        fmt::format(
            "burst \"{}\": expected position:begin_s:end_s:amplitude_A:offset_A:f0_hz:f1_hz "
            "with position 1 or 2",
            text),
        option("--burst"));
  return {static_cast<int>(v[0]), {v[1], v[2], v[3], v[4], v[5], v[6]}};
}

// "a:b:c" → numbers (`what` names the option in errors); `count` of them expected.
std::vector<double> colon_numbers(const std::string& text, const char* what, std::size_t count) {
  std::vector<double> v = split_colon_numbers(text, what, "");
  if (v.size() != count)
    throw InputError(fmt::format("\"{}\": expected {} numbers separated by ':'", text, count),
                     option(what));
  return v;
}

maglev::DeterminationSimulation SimulateArgs::determination() const {
  maglev::DeterminationSimulation s;
  s.truth.latitude_rad = angle_option(latitude, "--latitude");
  s.truth.alpha1_rad = angle_option(alpha1, "--alpha1");
  s.truth.scale_A_s_per_rad = scale;
  s.truth.bias_A = bias;
  s.truth.circle_reading1_rad = angle_option(reading1, "--reading1");
  s.noise = noise;
  for (const auto& b : bursts) s.bursts.push_back(parse_burst(b));
  for (const auto& t : steps) {
    const auto v = colon_numbers(t, "--step", 3);
    if (v[0] != 1 && v[0] != 2)
      throw InputError(fmt::format("step \"{}\": the position must be 1 or 2", t), option("--step"));
    s.steps.push_back({static_cast<int>(v[0]), {v[1], v[2]}});
  }
  if (!settling.empty()) {
    const auto v = colon_numbers(settling, "--settling", 2);
    s.noise.settling_A = v[0];
    s.noise.settling_tau_s = v[1];
  }
  s.sequence.clear();
  for (const auto& p : sequence) {
    if (p != "1" && p != "2")
      throw InputError(fmt::format("sequence: \"{}\" is not a position (1 or 2)", p),
                       option("--sequence"));
    s.sequence.push_back(p == "1" ? 1 : 2);
  }
  s.pause_s = pause;
  s.drift_restarts = drift_restarts;
  s.seed = seed;
  return s;
}

maglev::CalibrationSimulation SimulateArgs::calibration() const {
  maglev::CalibrationSimulation s;
  s.latitude_rad = angle_option(latitude, "--latitude");
  for (const auto& a : calibration_azimuths)
    s.azimuths_rad.push_back(angle_option(a, "--calibration-azimuths"));
  s.scale_A_s_per_rad = scale;
  s.slope_ratio1 = slope_ratio1;
  s.slope_ratio2 = slope_ratio2;
  s.best_azimuth_rad = angle_option(best_azimuth, "--best-azimuth");
  s.constant_deviation_A = constant_deviation;
  s.noise = noise;
  s.seed = seed;
  return s;
}

int run_simulate(const SimulateArgs& a, const std::string& command) {
  if (!a.calibration_azimuths.empty()) {
    const maglev::CalibrationInput table = maglev::simulate_calibration(a.calibration());
    emit(a.out + "-calibration.csv", io::maglev_calibration_csv(table, "made by: " + command));
    return kOk;
  }
  const maglev::DeterminationSimulation sim = a.determination();
  const maglev::ReduceInput in = maglev::simulate_determination(sim);
  const std::string header = io::maglev_truth_comment(command, sim.truth);
  if (a.one_file) {
    emit(a.out + ".csv", io::maglev_two_position_csv(in.position1, in.position2, header));
    return kOk;
  }
  const std::string p1 = io::maglev_series_csv(in.position1, header + "\nposition 1");
  const std::string p2 = io::maglev_series_csv(in.position2, header + "\nposition 2");
  emit(a.out + "-1.csv", p1);
  emit(a.out + "-2.csv", p2);
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
  check_output_paths({{a.output, "-o", "output"}, {a.report, "--report", "report"}}, {a.file});
  const maglev::CalibrationResult r = io::run_maglev_calibrate_file(
      a.file, angle_option(a.latitude, "--latitude"), a.alpha, a.nominal_scale);
  const std::string out = a.json ? report::json_text(report::maglev_calibration_to_json(r))
                                 : report::maglev_calibration_text(r);
  emit_with_report(a.output, out, a.report,
                   [&] { return report::render_html(report::maglev_calibration_document(r)); });
  return kOk;
}

void add_reduce_command(CLI::App* mg, int& exit_code) {
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
  red->add_option("--drift", ra->drift,
                  "Common drift on the positions' clock, fitted with the levels: none | linear | "
                  "quadratic")
      ->check(CLI::IsMember({"none", "linear", "quadratic"}))
      ->capture_default_str();
  red->add_option("--settling-cut", ra->settling_cut,
                  "Cut this many seconds at the start of every block (default: detected by an "
                  "exponential fitted and tested)")
      ->check(CLI::NonNegativeNumber);
  red->add_flag("--no-settling-detect", ra->no_settling_detect,
                "Do not look for a settling transient at the start of each block");
  red->add_option("--segment", ra->segment,
                  "Segment length in samples, >= 32 (0: about 20 segments)")
      ->check(segment_length())
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
}

void add_denoise_command(CLI::App* mg, int& exit_code) {
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
}

// The simulate command as typed (the options given, `--name=value`), for the files' header.
std::string simulate_command_line(const CLI::App* sim) {
  std::string cmd = "meridian maglev simulate";
  for (const CLI::Option* o : sim->get_options()) {
    if (o->count() == 0 || o->get_lnames().empty()) continue;
    const std::string name = o->get_lnames().front();
    if (name == "help" || name == "out") continue;
    cmd += " --" + name;
    if (o->get_expected_min() == 0) continue;
    std::string value;
    for (const auto& r : o->results()) value += (value.empty() ? "" : ",") + r;
    if (name == "burst" || name == "step")
      value = fmt::format("{}", fmt::join(o->results(), " --" + name + "="));
    cmd += "=" + value;
  }
  return cmd;
}

void add_simulate_command(CLI::App* mg, int& exit_code) {
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
  sim->add_option("--samples", sa->noise.samples, "Samples per block (per position for the default 1,2)")->capture_default_str();
  sim->add_option("--rate-hz", sa->noise.rate_hz, "Sample rate")->capture_default_str();
  sim->add_option("--white", sa->noise.white_sigma_A, "White noise sigma (A)")
      ->capture_default_str();
  sim->add_option("--ar1-phi", sa->noise.ar1_phi, "AR(1) coefficient")->capture_default_str();
  sim->add_option("--ar1-sigma", sa->noise.ar1_sigma_A, "AR(1) innovation sigma (A)")
      ->capture_default_str();
  sim->add_option("--drift", sa->noise.drift_A_per_s,
                  "Drift (A/s), continuous on the common clock of all blocks")
      ->capture_default_str();
  sim->add_option("--drift-quadratic", sa->noise.drift_quadratic_A_per_s2,
                  "Quadratic drift term (A/s^2) on the common clock")
      ->capture_default_str();
  sim->add_flag("--drift-restarts", sa->drift_restarts,
                "Restart the drift at each block (it then cancels; not what instruments do)");
  sim->add_option("--sequence", sa->sequence,
                  "Positions of the blocks in time order, e.g. 1,2,2,1 (default 1,2)")
      ->delimiter(',');
  sim->add_option("--pause", sa->pause, "Seconds between blocks (the rotation)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  sim->add_option("--settling", sa->settling,
                  "Settling after each rotation AMP_A:TAU_s (+AMP at position 1, -AMP at 2)");
  sim->add_option("--step", sa->steps,
                  "Step of the current position:time_s:size_A, time from the start of that "
                  "position's first block (repeatable)");
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
    exit_code = guarded([&] { return run_simulate(*sa, simulate_command_line(sim)); });
  });
}

void add_calibrate_command(CLI::App* mg, int& exit_code) {
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

}  // namespace
}  // namespace maglev_cmd

void add_maglev_commands(CLI::App& app, int& exit_code) {
  CLI::App* mg =
      app.add_subcommand("maglev", "Magnetically suspended gyro: two-position north seeking");
  mg->require_subcommand(1);
  maglev_cmd::add_reduce_command(mg, exit_code);
  maglev_cmd::add_denoise_command(mg, exit_code);
  maglev_cmd::add_simulate_command(mg, exit_code);
  maglev_cmd::add_calibrate_command(mg, exit_code);
}

}  // namespace meridian::cli
