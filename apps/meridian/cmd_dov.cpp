// meridian dov simulate | process | convert

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <system_error>

#include <fmt/format.h>

#include "cli_support.hpp"
#include "commands.hpp"
#include "meridian/core/atomic_file.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/dov/simulator.hpp"
#include "meridian/io/dov_binary.hpp"
#include "meridian/io/dov_jobs.hpp"
#include "meridian/io/dov_writers.hpp"
#include "meridian/report/dov_html.hpp"
#include "meridian/report/dov_outputs.hpp"
#include "meridian/report/html.hpp"
#include "meridian/report/json_text.hpp"

namespace meridian::cli {
namespace dov_cmd {
namespace {

struct SimulateArgs {
  std::string latitude = "30", longitude = "114", heading = "60";
  double speed_m_s = 5.0, rate_hz = 1.0, hours = 4.0, height_m = 0.0;
  double sigma_model_arcsec = 3.0, sigma_ins_arcsec = 0.5, eps_u_deg_per_h = 0.003;
  double phi_e_arcsec = 0.0, phi_n_arcsec = 0.0, phi_u_arcsec = 0.0;
  std::uint64_t seed = 1;
  std::string out;  // default dov-line.csv, or dov-line.bin with --binary
  std::string config;
  bool binary = false;
  bool transport_rate = false;
};

// The simulator's options from the command line's, checked in the options' own terms (the
// simulator's checks name its members in radians: a user trial found "simulation.start_lat_rad
// … 1.658" for --latitude 95).
dov::SimulationOptions simulation_options(const SimulateArgs& a) {
  dov::SimulationOptions so;
  so.start_lat_rad = angle_option(a.latitude, "--latitude");
  so.start_lon_rad = angle_option(a.longitude, "--longitude");
  so.heading_rad = angle_option(a.heading, "--heading");
  so.height_m = a.height_m;
  so.speed_m_s = a.speed_m_s;
  so.rate_hz = a.rate_hz;
  so.duration_s = a.hours * 3600.0;
  so.truth_model.sigma_model_rad = a.sigma_model_arcsec * units::kArcsecond;
  so.sigma_ins_rad = a.sigma_ins_arcsec * units::kArcsecond;
  so.eps_u_rad_s = a.eps_u_deg_per_h * units::kDegree / 3600.0;
  so.initial_attitude_error_rad =
      Eigen::Vector3d(a.phi_e_arcsec, a.phi_n_arcsec, a.phi_u_arcsec) * units::kArcsecond;
  so.seed = a.seed;
  so.transport_rate = a.transport_rate;
  if (!(std::abs(so.start_lat_rad) < 89.0 * units::kDegree))
    throw InputError(fmt::format("--latitude must be strictly between -89° and 89°, is {:.6g}°",
                                 so.start_lat_rad / units::kDegree));
  if (!(a.rate_hz > 0.0) || !std::isfinite(a.rate_hz))
    throw InputError(fmt::format("--rate-hz must be > 0 (samples per second), is {}", a.rate_hz));
  if (!(a.hours * 3600.0 * a.rate_hz >= 1.0))
    throw InputError(fmt::format("--hours {} at --rate-hz {} gives less than one step", a.hours,
                                 a.rate_hz));
  return so;
}

// The truth of the simulation, as gyro simulate records it: what produced this line.
std::string settings_text(const SimulateArgs& a) {
  return fmt::format(
             "Simulated: seed {}, start {} {}, heading {}, height {} m, speed {} m/s, {} Hz, {} h, "
             "sigma_model {}\", sigma_ins {}\", eps_U {} deg/h, phi(0) E N U = {} {} {}\"",
             a.seed, a.latitude, a.longitude, a.heading, a.height_m, a.speed_m_s, a.rate_hz,
             a.hours, a.sigma_model_arcsec, a.sigma_ins_arcsec, a.eps_u_deg_per_h, a.phi_e_arcsec,
             a.phi_n_arcsec, a.phi_u_arcsec) +
         (a.transport_rate ? ", attitude error with transport rate" : "");
}

int run_simulate(SimulateArgs a) {
  if (a.out.empty()) a.out = a.binary ? "dov-line.bin" : "dov-line.csv";
  const dov::SimulationOptions so = simulation_options(a);
  dov::Input in;
  try {
    in = dov::simulate(so);
  } catch (const InputError& e) {
    if (e.context().field != "simulation.duration_s") throw;
    throw InputError(fmt::format("the track leaves ±89° of latitude within --hours {} ({}): "
                                 "shorten the line or change --heading or --speed-m-s",
                                 a.hours, e.message()));
  }
  if (a.binary && a.out == "-")
    throw InputError("--binary needs --out to name a file (no binary on standard output)");
  const std::string line =
      a.binary ? io::dov_line_binary(in) : io::dov_line_csv(in, settings_text(a));
  if (a.config.empty()) {
    emit(a.out, line);
    return kOk;
  }
  if (a.out == "-")
    throw InputError("--config needs --out to name a file: the configuration names the line");
  if (same_path(a.out, a.config))
    throw InputError(fmt::format("--out and --config name the same file {}", a.out));
  // Both files or neither (a configuration in a missing directory used to leave the line).
  emit_all({{a.out, line},
            {a.config, io::dov_simulation_config_yaml({a.config, a.out, a.sigma_model_arcsec,
                                                       a.sigma_ins_arcsec, a.transport_rate})}});
  return kOk;
}

struct ProcessArgs {
  std::string config, output, report;
  bool json = false, quiet = false;
};


// An output written while the line streams (--output, --report): a temporary file beside its
// path, created now so that a path that cannot be written fails before the work, renamed into
// place by commit(); "-": held for standard output, written by commit().
class StreamedOutput {
 public:
  explicit StreamedOutput(const std::string& path) : path_(path) {
    if (!path.empty() && path != "-") file_.emplace(path);
  }
  void write(const std::string& text) {
    if (file_)
      file_->write(text);
    else
      held_ += text;
  }
  void commit() {
    if (file_)
      file_->commit();
    else if (!path_.empty())
      emit(path_, held_);
  }

 private:
  std::string path_;
  std::optional<AtomicFileWriter> file_;
  std::string held_;
};

int run_process(const ProcessArgs& a) {
  require_html_reports_for(a.report);
  const io::DovConfig c = io::read_dov_config(a.config);
  // The outputs must not replace each other, the line they are computed from or the configuration.
  check_output_paths({{a.output, "--output", "profile"}, {a.report, "--report", "report"}}, {c.line_path, a.config});
  TerminalProgress progress(a.quiet);
  StreamedOutput profile_file(a.output), report_file(a.report);
  report::DovProfileCsv profile;  // written out 1 MB at a time
  dov::EpochOutputs outputs;
  if (!a.output.empty())
    outputs.sink = [&](const dov::EpochResult& e) {
      profile.add(e);
      if (profile.text().size() > (std::size_t{1} << 20)) {
        profile_file.write(profile.text());
        profile.text().clear();
      }
    };
  if (!a.report.empty()) outputs.keep_epochs = report::kDovReportEpochs;
  const dov::Result r = io::run_dov_stream(c, outputs, &progress);
  // Everything is computed before anything is renamed into place.
  const std::string text = a.json ? report::json_text(report::dov_summary_to_json(r))
                                  : report::dov_summary_text(r);
  if (!a.report.empty()) report_file.write(report::render_html(report::dov_document(r)));
  profile_file.write(profile.text());
  profile_file.commit();
  report_file.commit();
  emit("", text);
  return kOk;
}

struct ConvertArgs {
  std::string input, output;
};

// A line CSV to the binary format or back (an OUT ending in .csv, or -), a block at a time.
int run_convert(const ConvertArgs& a) {
  if (a.output.empty())
    throw InputError("give the output file (OUT ending in .csv, or -, for a CSV)");
  std::error_code ec;
  if (same_path(a.input, a.output) || std::filesystem::equivalent(a.input, a.output, ec))
    throw InputError(fmt::format("the output would overwrite the input {}", a.input));
  std::cerr << io::dov_conversion_text(io::convert_dov_line(a.input, a.output, std::cout));
  return kOk;
}

void add_simulate_command(CLI::App* dv, int& exit_code) {
  auto sa = std::make_shared<SimulateArgs>();
  CLI::App* sim = dv->add_subcommand(
      "simulate", "Simulate a line (spec section 7): both attitude solutions, model and truth");
  sim->add_option("--latitude", sa->latitude, "Start latitude (DMS or deg)")->capture_default_str();
  sim->add_option("--longitude", sa->longitude, "Start longitude (DMS or deg)")
      ->capture_default_str();
  sim->add_option("--heading", sa->heading, "Heading, clockwise from north (DMS or deg)")
      ->capture_default_str();
  sim->add_option("--height-m", sa->height_m, "Ellipsoidal height (m)")->capture_default_str();
  sim->add_option("--speed-m-s", sa->speed_m_s, "Speed V (m/s)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  sim->add_option("--rate-hz", sa->rate_hz, "Sample rate (Hz), > 0")->capture_default_str();
  sim->add_option("--hours", sa->hours, "Duration (h)")->check(CLI::PositiveNumber)->capture_default_str();
  sim->add_option("--sigma-model-arcsec", sa->sigma_model_arcsec,
                  "Sigma of the global model's error (arcsec)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  sim->add_option("--sigma-ins-arcsec", sa->sigma_ins_arcsec, "INS/GNSS white noise (arcsec)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  sim->add_option("--eps-u-deg-per-h", sa->eps_u_deg_per_h, "Vertical gyro bias (deg/h)")
      ->capture_default_str();
  sim->add_option("--phi-e-arcsec", sa->phi_e_arcsec, "Initial LGU error phi_E (arcsec)");
  sim->add_option("--phi-n-arcsec", sa->phi_n_arcsec, "Initial LGU error phi_N (arcsec)");
  sim->add_option("--phi-u-arcsec", sa->phi_u_arcsec, "Initial LGU error phi_U (arcsec)");
  sim->add_option("--seed", sa->seed, "Random seed")->capture_default_str();
  sim->add_option("--out", sa->out,
                  "Line to write (default dov-line.csv, with --binary dov-line.bin; - for "
                  "standard output, CSV only)");
  sim->add_option("--config", sa->config, "Also write a configuration naming the line");
  sim->add_flag("--binary", sa->binary,
                "Write the line in the compact binary format (docs/file-formats.md)");
  sim->add_flag("--transport-rate", sa->transport_rate,
                "The true LGU attitude error also turns with the transport rate (fast carriers; "
                "--config then sets transport_rate: true)");
  sim->callback([sa, &exit_code] { exit_code = guarded([&] { return run_simulate(*sa); }); });
}

void add_process_command(CLI::App* dv, int& exit_code) {
  auto pa = std::make_shared<ProcessArgs>();
  CLI::App* pro = dv->add_subcommand(
      "process", "Filter and smooth a line: eta, xi with sigma per epoch (config in YAML)");
  pro->add_option("CONFIG", pa->config, "YAML or JSON configuration (docs/deflection.md)")
      ->required();
  pro->add_flag("--json", pa->json, "Print the summary as JSON");
  pro->add_option("-o,--output", pa->output, "Write the per-epoch profile CSV here");
  pro->add_option("--report", pa->report, "Write an HTML report (profile with ±σ, innovations)");
  pro->add_flag("-q,--quiet", pa->quiet, "No progress bar");
  pro->callback([pa, &exit_code] { exit_code = guarded([&] { return run_process(*pa); }); });
}

void add_convert_command(CLI::App* dv, int& exit_code) {
  auto ca = std::make_shared<ConvertArgs>();
  CLI::App* conv = dv->add_subcommand(
      "convert",
      "Convert a line CSV to the compact binary line format, or (OUT ending in .csv, or -) a "
      "binary line to CSV (docs/file-formats.md)");
  conv->add_option("IN", ca->input, "Line CSV or binary line")->required();
  conv->add_option("OUT", ca->output,
                   "Binary line to write (atomically); a name ending in .csv gets a line CSV, - "
                   "standard output")
      ->required();
  conv->callback([ca, &exit_code] { exit_code = guarded([&] { return run_convert(*ca); }); });
}

}  // namespace
}  // namespace dov_cmd

void add_dov_commands(CLI::App& app, int& exit_code) {
  CLI::App* dv = app.add_subcommand(
      "dov", "Dynamic deflection of the vertical from INS/GNSS attitude differences");
  dv->require_subcommand(1);
  dov_cmd::add_simulate_command(dv, exit_code);
  dov_cmd::add_process_command(dv, exit_code);
  dov_cmd::add_convert_command(dv, exit_code);
}

}  // namespace meridian::cli
