// meridian gyro reduce | campaign | orientations | simulate | transit-factor | template | stochastic

#include <filesystem>
#include <cstdio>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cli_support.hpp"
#include "commands.hpp"
#include "meridian/core/error.hpp"
#include "meridian/io/gyro_jobs.hpp"
#include "meridian/io/gyro_simulate.hpp"
#include "meridian/io/gyro_writers.hpp"
#include "meridian/report/gyro_html.hpp"
#include "meridian/report/gyro_json.hpp"
#include "meridian/report/gyro_stochastic.hpp"
#include "meridian/report/gyro_text.hpp"
#include "meridian/report/html.hpp"
#include "meridian/report/json_text.hpp"

namespace meridian::cli {
namespace gyro_cmd {
namespace {

struct ReduceArgs {
  std::string file, output, report;
  bool json = false, quiet = false;
};

int run_reduce(const ReduceArgs& a) {
  require_html_reports_for(a.report);
  check_output_paths({{a.output, "-o", "output"}, {a.report, "--report", "report"}}, {a.file});
  TerminalProgress progress(a.quiet);
  const gyro::ReduceResult r = io::run_reduce_file(a.file, &progress).result;
  progress.finish();
  // Everything is computed before anything is written.
  const std::string out = a.json ? report::json_text(report::reduce_to_json(r))
                                 : report::reduce_text(r, report::AngleFormat(r.input.angle_unit));
  emit_with_report(a.output, out, a.report, [&] { return report::render_html(report::gyro_reduce_document(r)); });
  return kOk;
}

struct StochasticArgs {
  std::string file, output, report;
  bool json = false, quiet = false;
};

int run_stochastic(const StochasticArgs& a) {
  require_html_reports_for(a.report);
  check_output_paths({{a.output, "-o", "output"}, {a.report, "--report", "report"}}, {a.file});
  TerminalProgress progress(a.quiet);
  const gyro::StochasticBookResult r = io::run_stochastic_file(a.file, &progress);
  progress.finish();
  const std::string out = a.json ? report::json_text(report::stochastic_to_json(r)) : report::stochastic_text(r);
  emit_with_report(a.output, out, a.report, [&] { return report::render_html(report::stochastic_document(r)); });
  return kOk;
}

struct CampaignArgs {
  std::string file, output, report;
  bool json = false, strict = false, quiet = false;
};

// --strict and a failed check: say which on stderr, one line each, with where it was booked
// ("job.yaml:200: line.determinations[1].target_rounds[0]: ") when `place` knows.
void print_failed_checks(const std::vector<gyro::Check>& checks,
                         const std::function<ErrorContext(const gyro::Check&)>& place = {}) {
  std::size_t failed = 0;
  for (const gyro::Check& c : checks) {
    if (c.pass) continue;
    ++failed;
    std::string where;
    if (place) {
      const ErrorContext p = place(c);
      if (!p.file.empty()) where += p.file + ":";
      if (p.line) where += std::to_string(*p.line) + ":";
      if (!p.field.empty()) where += (where.empty() ? "" : " ") + p.field + ":";
      if (!where.empty()) where += " ";
    }
    std::cerr << "meridian: " << where << "check failed: " << report::check_statement(c) << "\n";
  }
  std::cerr << fmt::format("meridian: --strict: {} check{} failed; no output file written\n", failed,
                           failed == 1 ? "" : "s");
}

int run_campaign(const CampaignArgs& a) {
  require_html_reports_for(a.report);
  check_output_paths({{a.output, "-o", "output"}, {a.report, "--report", "report"}}, {a.file});
  TerminalProgress progress(a.quiet);
  const io::CampaignJob job = io::run_campaign_file(a.file, nullptr, &progress);
  const gyro::CampaignResult& r = job.result;
  progress.finish();
  const std::string out = a.json ? report::json_text(report::campaign_to_json(r))
                                 : report::campaign_text(r, report::AngleFormat(r.input.angle_unit));
  if (a.strict && !r.all_checks_pass()) {
    // A job that fails its checks is not filed: stdout still shows it, no file is written.
    if (a.output.empty() || a.output == "-") emit("", out);
    print_failed_checks(r.checks, [&](const gyro::Check& c) { return io::check_place(job, c); });
    return kInputError;
  }
  emit_with_report(a.output, out, a.report, [&] { return report::render_html(report::gyro_campaign_document(r)); });
  return kOk;
}

struct TemplateArgs {
  std::string kind = "campaign", output;
};

int run_template(const TemplateArgs& a) {
  if (a.kind == "campaign") emit(a.output, io::campaign_template_yaml());
  else if (a.kind == "reduce") emit(a.output, io::reduce_template_yaml());
  else
    throw InputError("unknown kind \"" + a.kind + "\" (expected campaign or reduce)", {"", std::nullopt, "--kind"});
  return kOk;
}

struct OrientationsArgs {
  std::vector<std::string> files;
  std::string output, report;
  bool json = false, strict = false, quiet = false;
};

int run_orientations(const OrientationsArgs& a) {
  require_html_reports_for(a.report);
  check_output_paths({{a.output, "-o", "output"}, {a.report, "--report", "report"}}, a.files);
  TerminalProgress progress(a.quiet);
  std::vector<std::filesystem::path> paths(a.files.begin(), a.files.end());
  const io::OrientationsJob job = io::run_orientation_files(paths, &progress);
  progress.finish();
  const report::AngleFormat f(job.orientations.front().result.input.angle_unit);
  const std::string out = a.json ? report::json_text(report::orientations_to_json(job.result))
                                 : report::orientations_text(job.result, f);
  if (a.strict && !job.result.all_checks_pass()) {
    if (a.output.empty() || a.output == "-") emit("", out);
    // A check about orientation j names its file.
    print_failed_checks(job.result.checks, [&](const gyro::Check& c) {
      unsigned j = 0;
      if (std::sscanf(c.field.c_str(), "orientations[%u]", &j) == 1 && j < job.result.files.size())
        return ErrorContext{job.result.files[j], std::nullopt, c.field};
      return ErrorContext{"", std::nullopt, c.field};
    });
    return kInputError;
  }
  emit_with_report(a.output, out, a.report, [&] {
    std::vector<gyro::CampaignResult> results;
    for (const auto& o : job.orientations) results.push_back(o.result);
    return report::render_html(report::gyro_orientations_document(job.result, results));
  });
  return kOk;
}

struct TransitArgs {
  std::string file;
  bool json = false;
};

int run_transit_factor(const TransitArgs& a) {
  const gyro::TransitFactorCalibration c = io::run_transit_factor_file(a.file);
  emit("", a.json ? report::json_text(report::transit_factor_to_json(c)) : report::transit_factor_text(c));
  return kOk;
}

// The options of `gyro simulate`: the runner's settings (io::SimulateSettings) and the output.
struct SimulateArgs {
  io::SimulateSettings settings;
  std::string output;
  bool quiet = false;
};

int run_simulate(const SimulateArgs& a) {
  TerminalProgress progress(a.quiet);
  const io::SimulatedBook book = io::run_simulation(a.settings, &progress);
  progress.finish();
  emit(a.output, io::simulated_book_yaml(book));
  return kOk;
}

// The command line of `gyro simulate` as it can be typed again (the options that shape the
// data), and the long names of the options given.
void record_typed_options(const CLI::App& sim, io::SimulateSettings& s) {
  s.command_line = "meridian gyro simulate";
  s.given.clear();
  for (const CLI::Option* o : sim.get_options()) {
    if (o->count() == 0 || o->get_lnames().empty()) continue;
    const std::string name = o->get_lnames().front();
    s.given.push_back(name);
    if (name == "help" || name == "output" || name == "quiet") continue;
    s.command_line += " --" + name;
    if (o->get_expected_min() == 0) continue;
    std::string value;
    for (const auto& r : o->results()) value += (value.empty() ? "" : ",") + r;
    s.command_line += value.find(' ') == std::string::npos ? " " + value : " \"" + value + "\"";
  }
}

// --- one function per subcommand: its options and its callback

void add_reduce(CLI::App& gyro, int& exit_code) {
  auto ra = std::make_shared<ReduceArgs>();
  CLI::App* reduce = gyro.add_subcommand("reduce", "Reduce the determinations in a YAML/JSON file to N_G");
  reduce->add_option("FILE", ra->file, "Input file (YAML, or JSON as is)")->required();
  reduce->add_flag("--json", ra->json, "Print one JSON object instead of text");
  reduce->add_option("-o,--output", ra->output, "Write to this file (atomically) instead of stdout");
  reduce->add_option("--report", ra->report, "Also write a self-contained HTML report (plots, tables) to this file");
  reduce->add_flag("-q,--quiet", ra->quiet, "No progress bar");
  reduce->callback([ra, &exit_code] { exit_code = guarded([&] { return run_reduce(*ra); }); });
}

void add_campaign(CLI::App& gyro, int& exit_code) {
  auto ca = std::make_shared<CampaignArgs>();
  CLI::App* camp = gyro.add_subcommand("campaign", "Process a whole station campaign to grid azimuths");
  camp->add_option("FILE", ca->file, "Campaign file (YAML or JSON)")->required();
  camp->add_flag("--json", ca->json, "Print JSON instead of text");
  camp->add_flag("--strict", ca->strict,
                 "When a tolerance check fails: list the failed checks on stderr, write no output file, exit 1");
  camp->add_option("-o,--output", ca->output, "Write to this file (atomically) instead of stdout");
  camp->add_option("--report", ca->report, "Also write a self-contained HTML report (plots, tables) to this file");
  camp->add_flag("-q,--quiet", ca->quiet, "No progress bar");
  camp->callback([ca, &exit_code] { exit_code = guarded([&] { return run_campaign(*ca); }); });
}

void add_template(CLI::App& gyro, int& exit_code) {
  auto tp = std::make_shared<TemplateArgs>();
  CLI::App* tmpl = gyro.add_subcommand("template", "Write a commented field book to start from");
  tmpl->add_option("--kind", tp->kind, "campaign (a whole 3-2-3 job) | reduce (the runs of one station)")
      ->capture_default_str();
  tmpl->add_option("-o,--output", tp->output, "Write to this file (atomically) instead of stdout");
  tmpl->callback([tp, &exit_code] { exit_code = guarded([&] { return run_template(*tp); }); });
}

void add_orientations(CLI::App& gyro, int& exit_code) {
  auto oa = std::make_shared<OrientationsArgs>();
  CLI::App* ori = gyro.add_subcommand(
      "orientations", "Two or more independent orientations of one line (campaign files): difference and mean");
  ori->add_option("FILES", oa->files, "Campaign files, one per independent orientation")->required()->expected(2, -1);
  ori->add_flag("--json", oa->json, "Print JSON instead of text");
  ori->add_flag("--strict", oa->strict, "Exit with code 1 when a check fails (and write nothing)");
  ori->add_option("-o,--output", oa->output, "Write to this file (atomically) instead of stdout");
  ori->add_option("--report", oa->report, "Also write a self-contained HTML result sheet (成果表) to this file");
  ori->add_flag("-q,--quiet", oa->quiet, "No progress bar");
  ori->callback([oa, &exit_code] { exit_code = guarded([&] { return run_orientations(*oa); }); });
}

void add_transit_factor(CLI::App& gyro, int& exit_code) {
  auto ta = std::make_shared<TransitArgs>();
  CLI::App* tf = gyro.add_subcommand(
      "transit-factor", "Empirical transit factor c from two transit determinations (east/west clamp)");
  tf->add_option("FILE", ta->file, "Reduce-format file with exactly two non-tracking determinations")->required();
  tf->add_flag("--json", ta->json, "Print JSON");
  tf->callback([ta, &exit_code] { exit_code = guarded([&] { return run_transit_factor(*ta); }); });
}

// The options of the station (non-tracking and tracking) simulations.
void add_station_options(CLI::App* sim, io::SimulateSettings& s) {
  sim->add_option("--determinations", s.sim.determinations, "Number of determinations (seeds seed, seed+1, ...)")->capture_default_str();
  sim->add_option("--tau-arcsec", s.tau_arcsec, "Scale value tau (arcsec/div)")->capture_default_str();
  sim->add_option("--lambda", s.sim.torsion_ratio, "Torsion ratio lambda at the station")->capture_default_str();
  sim->add_option("--latitude-deg", s.latitude_deg, "Station latitude (deg)")->capture_default_str();
  sim->add_option("--spin-momentum-Nms", s.spin_momentum_Nms, "H: derive periods and lambda from physics");
  sim->add_option("--inertia-kgm2", s.inertia_kgm2, "J_z (with --spin-momentum-Nms)");
  sim->add_option("--torsion-Nm-per-rad", s.torsion_Nm_per_rad, "D_B (with --spin-momentum-Nms)");
  sim->add_option("--beta-div", s.sim.beta_div, "Non-tracking: equilibrium reading beta (div)")->capture_default_str();
  sim->add_option("--amplitude-div", s.sim.amplitude_div, "Non-tracking: amplitude B (div)")->capture_default_str();
  sim->add_option("--period-s", s.sim.period_s, "Non-tracking: period T_B (s)")->capture_default_str();
  sim->add_option("--t0-s", s.sim.t0_s, "Non-tracking: eastward passage of beta (s)")->capture_default_str();
  sim->add_option("--damping-per-s", s.sim.damping_per_s, "Non-tracking: damping k (1/s)")->capture_default_str();
  sim->add_option("--levels", s.sim.levels_div, "Non-tracking: graduations to time (div)")->delimiter(',')->capture_default_str();
  sim->add_option("--crossings", s.sim.crossings_per_level, "Non-tracking: crossings per level")->capture_default_str();
  sim->add_option("--reversals", s.sim.reversals, "Non-tracking: reversal readings")->capture_default_str();
  sim->add_option("--clamp", s.clamps,
                  "Non-tracking: clamp reading N' (DMS or deg); a comma-separated list clamps the determinations in "
                  "turn at the same gyro north (beta is for the first)")
      ->delimiter(',')
      ->capture_default_str();
}

void add_simulate(CLI::App& gyro, int& exit_code) {
  auto sa = std::make_shared<SimulateArgs>();
  io::SimulateSettings& s = sa->settings;
  CLI::App* sim = gyro.add_subcommand("simulate", "Simulate observations (writes a reduce or campaign file)");
  sim->add_option("--mode", s.mode, "non-tracking | tracking | campaign")->capture_default_str();
  sim->add_option("--seed", s.seed, "Random seed (runs are reproducible)")->capture_default_str();
  sim->add_option("-o,--output", sa->output, "Output file (default stdout)");
  add_station_options(sim, s);
  sim->add_option("--sigma-time-s", s.sim.sigma_time_s, "Timing noise sigma (s)")->capture_default_str();
  sim->add_option("--sigma-reading-div", s.sim.sigma_reading_div, "Scale reading noise sigma (div)")->capture_default_str();
  sim->add_flag("!--unknown-period", s.sim.known_period, "Do not write period_s into the file");
  sim->add_option("--centre", s.centre, "Tracking: centre M (DMS or deg)")->capture_default_str();
  sim->add_option("--tracking-amplitude-div", s.sim.tracking_amplitude_div, "Tracking: amplitude A (div of tau)")->capture_default_str();
  sim->add_option("--kappa", s.sim.kappa, "Tracking: decay per half period")->capture_default_str();
  sim->add_option("--tracking-reversals", s.sim.tracking_reversals, "Tracking: number of reversals")->capture_default_str();
  sim->add_option("--sigma-tracking-arcsec", s.sigma_tracking_arcsec, "Tracking: reading noise sigma (arcsec)")->capture_default_str();
  sim->add_option("--noise", s.noise, "white | markov1 | markov2")->capture_default_str();
  sim->add_option("--sigma-initial-arcsec", s.sigma_initial_arcsec,
                  "Tracking, Markov noise: sigma_2 of the initial state(s) X (arcsec; default: --sigma-tracking-arcsec)");
  sim->add_option("--rho1", s.sim.rho1, "Markov coefficient rho1")->capture_default_str();
  sim->add_option("--rho2", s.sim.rho2, "Markov-2 coefficient rho2")->capture_default_str();
  sim->add_flag("-q,--quiet", sa->quiet, "No progress bar");
  sim->callback([sa, sim, &exit_code] {
    record_typed_options(*sim, sa->settings);
    exit_code = guarded([&] { return run_simulate(*sa); });
  });
}

void add_stochastic(CLI::App& gyro, int& exit_code) {
  auto sto = std::make_shared<StochasticArgs>();
  CLI::App* stoch = gyro.add_subcommand(
      "stochastic", "Compare stochastic models (white noise, covariance functions, Markov-1/-2) of each reversal series");
  stoch->add_option("FILE", sto->file, "Field book as for gyro reduce, or a campaign file (YAML or JSON)")->required();
  stoch->add_flag("--json", sto->json, "Print JSON instead of text");
  stoch->add_option("-o,--output", sto->output, "Write to this file (atomically) instead of stdout");
  stoch->add_flag("-q,--quiet", sto->quiet, "No progress bar");
  stoch->add_option("--report", sto->report,
                    "Also write a self-contained HTML report (comparison table, autocorrelation, Markov-2 likelihood surface)");
  stoch->callback([sto, &exit_code] { exit_code = guarded([&] { return run_stochastic(*sto); }); });
}

}  // namespace
}  // namespace gyro_cmd

void add_gyro_commands(CLI::App& app, int& exit_code) {
  CLI::App* gyro = app.add_subcommand("gyro", "Gyro-theodolite orientation");
  gyro->require_subcommand(1);
  gyro_cmd::add_reduce(*gyro, exit_code);
  gyro_cmd::add_campaign(*gyro, exit_code);
  gyro_cmd::add_template(*gyro, exit_code);
  gyro_cmd::add_orientations(*gyro, exit_code);
  gyro_cmd::add_transit_factor(*gyro, exit_code);
  gyro_cmd::add_simulate(*gyro, exit_code);
  gyro_cmd::add_stochastic(*gyro, exit_code);
}

}  // namespace meridian::cli
