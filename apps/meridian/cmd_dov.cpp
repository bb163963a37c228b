// meridian dov simulate | process

#include <cmath>
#include <cstdint>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "cli_support.hpp"
#include "commands.hpp"
#include "meridian/core/atomic_file.hpp"
#include "meridian/core/dms.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/dov/simulator.hpp"
#include "meridian/dov/streaming.hpp"
#include "meridian/io/dov_binary.hpp"
#include "meridian/io/dov_files.hpp"
#include "meridian/report/dov_html.hpp"
#include "meridian/report/dov_outputs.hpp"

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

int run_simulate(SimulateArgs a) {
  if (a.out.empty()) a.out = a.binary ? "dov-line.bin" : "dov-line.csv";
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
  // The simulator's own checks name its members in radians; say it in the options' terms
  // (a user trial found "simulation.start_lat_rad … 1.658" for --latitude 95).
  if (!(std::abs(so.start_lat_rad) < 89.0 * units::kDegree))
    throw InputError(fmt::format("--latitude must be strictly between -89° and 89°, is {:.6g}°",
                                 so.start_lat_rad / units::kDegree));
  if (!(a.rate_hz > 0.0) || !std::isfinite(a.rate_hz))
    throw InputError(fmt::format("--rate-hz must be > 0 (samples per second), is {}", a.rate_hz));
  if (!(a.hours * 3600.0 * a.rate_hz >= 1.0))
    throw InputError(fmt::format("--hours {} at --rate-hz {} gives less than one step", a.hours,
                                 a.rate_hz));
  dov::Input in;
  try {
    in = dov::simulate(so);
  } catch (const InputError& e) {
    if (e.context().field != "simulation.duration_s") throw;
    throw InputError(fmt::format("the track leaves ±89° of latitude within --hours {} ({}): "
                                 "shorten the line or change --heading or --speed-m-s",
                                 a.hours, e.message()));
  }
  // The truth of the simulation, as gyro simulate records it: what produced this line.
  const std::string settings = fmt::format(
      "Simulated: seed {}, start {} {}, heading {}, height {} m, speed {} m/s, {} Hz, {} h, "
      "sigma_model {}\", sigma_ins {}\", eps_U {} deg/h, phi(0) E N U = {} {} {}\"",
      a.seed, a.latitude, a.longitude, a.heading, a.height_m, a.speed_m_s, a.rate_hz, a.hours,
      a.sigma_model_arcsec, a.sigma_ins_arcsec, a.eps_u_deg_per_h, a.phi_e_arcsec, a.phi_n_arcsec,
      a.phi_u_arcsec) + (a.transport_rate ? ", attitude error with transport rate" : "");
  if (a.binary && a.out == "-")
    throw InputError("--binary needs --out to name a file (no binary on standard output)");
  const std::string csv = a.binary ? io::dov_line_binary(in) : io::dov_line_csv(in, settings);
  if (a.config.empty()) {
    emit(a.out, csv);
    return kOk;
  }
  if (a.out == "-")
    throw InputError("--config needs --out to name a file: the configuration names the line");
  if (same_path(a.out, a.config))
    throw InputError(fmt::format("--out and --config name the same file {}", a.out));
  // The configuration names the line relative to its own directory.
  const auto config_dir = std::filesystem::absolute(a.config).parent_path();
  const auto line = std::filesystem::relative(std::filesystem::absolute(a.out), config_dir);
  const std::string config = fmt::format("# meridian dov process configuration (spec defaults)\n"
                                         "line: {}\n"
                                         "sigma_model_arcsec: {}\n"
                                         "sigma_obs_arcsec: {}\n{}",
                                         line.string(), a.sigma_model_arcsec,
                                         a.sigma_ins_arcsec > 0.0 ? a.sigma_ins_arcsec : 0.5,
                                         a.transport_rate ? "transport_rate: true\n" : "");
  // Both files or neither: both temporaries exist before either is renamed into place (a
  // configuration in a missing directory used to leave the line written).
  AtomicFileWriter line_file(a.out), config_file(a.config);
  line_file.write(csv);
  config_file.write(config);
  line_file.commit();
  config_file.commit();
  return kOk;
}

// "egm96 (to degree 360)" as the configuration names it; the note gives the degree loaded.
std::string model_text(const io::DovGravityModel& m) {
  return m.max_degree > 0 ? fmt::format("{} (to degree {})", m.source, m.max_degree) : m.source;
}

struct ProcessArgs {
  std::string config, output, report;
  bool json = false, quiet = false;
};

// The epochs a report draws, kept while the line streams by: every `every`-th epoch, the
// spacing doubled whenever more than 2·kReportEpochs are held, so memory stays bounded.
class ReportEpochs {
 public:
  static constexpr std::size_t kReportEpochs = 2000;
  void add(const dov::EpochResult& e) {
    if (seen_++ % every_ != 0) return;
    kept_.push_back(e);
    if (kept_.size() > 2 * kReportEpochs) {
      std::size_t j = 0;
      for (std::size_t i = 0; i < kept_.size(); i += 2) kept_[j++] = kept_[i];
      kept_.resize(j);
      every_ *= 2;
    }
  }
  std::vector<dov::EpochResult>& kept() { return kept_; }
  std::size_t every() const { return every_; }

 private:
  std::vector<dov::EpochResult> kept_;
  std::size_t every_ = 1;
  std::size_t seen_ = 0;
};

struct ConvertArgs {
  std::string input, output;
};

bool names_csv(const std::string& path) {
  if (path == "-") return true;
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return ext == ".csv";
}

// The line of `reader` as a line CSV, a block at a time, atomically (or to stdout); returns
// the sample count.
std::uint64_t convert_to_csv(const ConvertArgs& a, io::DovLineReader& reader, bool model,
                             bool truth) {
  std::optional<AtomicFileWriter> file;
  if (a.output != "-") file.emplace(a.output);
  const auto put = [&](const std::string& text) {
    if (file)
      file->write(text);
    else
      std::cout << text;
  };
  put(io::dov_line_csv_header(model, truth, "Converted from " + a.input));
  io::DovLine chunk;
  std::string text;
  std::uint64_t count = 0;
  while (reader.next(chunk, 65536)) {
    text.clear();
    io::append_dov_line_csv_rows(text, chunk.samples, chunk.truth, model, truth);
    put(text);
    count += chunk.samples.size();
  }
  if (file) file->commit();
  return count;
}

// A line CSV (or binary) to the binary format, a block at a time: the header's count is
// written last (AtomicFileWriter::write_at), the file renamed into place only when complete.
// An OUT ending in .csv (or "-") is the other direction: convert_to_csv.
int run_convert(const ConvertArgs& a) {
  if (a.output.empty())
    throw InputError("give the output file (OUT ending in .csv, or -, for a CSV)");
  std::error_code ec;
  if (same_path(a.input, a.output) || std::filesystem::equivalent(a.input, a.output, ec))
    throw InputError(fmt::format("the output would overwrite the input {}", a.input));
  io::DovLineReader reader(a.input);
  const bool model = reader.has_model_values(), truth = reader.has_truth();
  const std::vector<std::string> ignored = reader.ignored_columns();
  if (!ignored.empty())  // neither output has room for them: say so before dropping them
    std::cerr << fmt::format("warning: {}: column{} {} not converted (not a line column; a "
                             "misspelt optional column is not read)\n",
                             a.input, ignored.size() == 1 ? "" : "s", fmt::join(ignored, ", "));
  const auto summary = [&](std::uint64_t count) {
    std::cerr << fmt::format("{}: {} samples{}{}\n", a.output == "-" ? "stdout" : a.output, count,
                             model ? ", model values" : ", no model values",
                             truth ? ", truth" : "");
    return kOk;
  };
  if (names_csv(a.output)) return summary(convert_to_csv(a, reader, model, truth));
  AtomicFileWriter out(a.output);
  out.write(io::dov_binary_header(0, model, truth));
  io::DovLine chunk;
  std::string bytes;
  std::uint64_t count = 0;
  while (reader.next(chunk, 65536)) {
    bytes.clear();
    for (std::size_t k = 0; k < chunk.samples.size(); ++k)
      io::append_dov_binary_record(bytes, chunk.samples[k], truth ? &chunk.truth[k] : nullptr,
                                   model, truth);
    out.write(bytes);
    count += chunk.samples.size();
  }
  out.write_at(0, io::dov_binary_header(count, model, truth));
  out.commit();
  return summary(count);
}

int run_process(const ProcessArgs& a) {
  require_html_reports_for(a.report);
  const io::DovConfig c = io::read_dov_config(a.config);
  // The outputs must not replace the line they are computed from (or the configuration).
  if (!a.output.empty() && !a.report.empty() && same_path(a.output, a.report))
    throw InputError(fmt::format("--output and --report name the same file {}", a.output));
  struct Output {
    const std::string& path;
    const char* option;
    const char* what;
  };
  for (const Output& o : {Output{a.output, "--output", "profile"}, Output{a.report, "--report", "report"}}) {
    if (o.path.empty()) continue;
    std::error_code ec;
    for (const std::string& in : {c.line_path, a.config})
      if (std::filesystem::equivalent(o.path, in, ec))
        throw InputError(fmt::format("the {} would overwrite the input {}", o.what, in),
                         {"", std::nullopt, o.option});
  }
  TerminalProgress progress(a.quiet);
  // The profile streams into a temporary file beside its path while the epochs come, and is
  // renamed into place only when everything is computed (atomic outputs).
  std::optional<AtomicFileWriter> profile, report_file;
  if (!a.output.empty() && a.output != "-") profile.emplace(a.output);
  // The report's temporary file too, now: a report that cannot be written fails before the
  // work, and never after the profile has been renamed into place.
  if (!a.report.empty() && a.report != "-") report_file.emplace(a.report);
  std::string buffer;
  bool header = false;
  ReportEpochs drawn;
  const auto flush = [&] {
    if (profile) profile->write(buffer);
    buffer.clear();
  };
  dov::EpochSink sink;
  if (!a.output.empty() || !a.report.empty())
    sink = [&](const dov::EpochResult& e) {
      if (!a.report.empty()) drawn.add(e);
      if (a.output.empty()) return;
      if (!header) {
        buffer = report::dov_profile_csv_header(e.truth.has_value());
        header = true;
      }
      report::append_dov_profile_line(buffer, e);
      if (profile && buffer.size() > (std::size_t{1} << 20)) flush();
    };
  const dov::LineResult line = io::run_dov_stream(c, sink, &progress);
  dov::Result r;
  r.summary = line.summary;
  r.notes = line.notes;
  r.warnings = line.warnings;
  const std::string text = a.json ? report::dov_summary_to_json(r, c.options).dump(2) + "\n"
                                  : report::dov_summary_text(r, c.options);
  std::string html;
  if (!a.report.empty()) {
    r.epochs = std::move(drawn.kept());
    html = report::render_html(report::dov_document(
        r, c.options, a.config, c.line_path,
        c.gravity_model ? model_text(*c.gravity_model) : std::string(), drawn.every()));
  }
  if (report_file) report_file->write(html);
  if (profile) {
    flush();
    profile->commit();
  } else if (!a.output.empty()) {
    emit(a.output, buffer);  // "-": standard output
  }
  if (report_file)
    report_file->commit();
  else if (!a.report.empty())
    emit(a.report, html);  // "-"
  emit("", text);
  return kOk;
}

}  // namespace
}  // namespace dov_cmd

void add_dov_commands(CLI::App& app, int& exit_code) {
  using namespace dov_cmd;  // the command's option structs and run functions
  CLI::App* dv = app.add_subcommand(
      "dov", "Dynamic deflection of the vertical from INS/GNSS attitude differences");
  dv->require_subcommand(1);

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

  auto pa = std::make_shared<ProcessArgs>();
  CLI::App* pro = dv->add_subcommand(
      "process", "Filter and smooth a line: eta, xi with sigma per epoch (config in YAML)");
  pro->add_option("CONFIG", pa->config, "YAML or JSON configuration (docs/deflection.md)")
      ->required();
  pro->add_flag("--json", pa->json, "Print the summary as JSON");
  pro->add_option("-o,--output", pa->output, "Write the per-epoch profile CSV here");
  pro->add_option("--report", pa->report, "Write an HTML report (profile with ±σ, innovations)");
  pro->add_flag("-q,--quiet", pa->quiet, "No progress bar");

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
  pro->callback([pa, &exit_code] { exit_code = guarded([&] { return run_process(*pa); }); });
}

}  // namespace meridian::cli
