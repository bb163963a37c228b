// meridian gyro reduce | campaign | orientations | simulate | transit-factor | template | stochastic

#include <cmath>
#include <iostream>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>


#include "cli_support.hpp"
#include "commands.hpp"
#include "meridian/core/dms.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gyro/campaign_simulator.hpp"
#include "meridian/gyro/station_simulator.hpp"
#include "meridian/io/gyro_jobs.hpp"
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

// --strict and a failed check: say which on stderr, one line each.
void print_failed_checks(const std::vector<gyro::Check>& checks) {
  std::size_t failed = 0;
  for (const gyro::Check& c : checks) {
    if (c.pass) continue;
    ++failed;
    std::cerr << "meridian: check failed: " << report::check_statement(c) << "\n";
  }
  std::cerr << fmt::format("meridian: --strict: {} check{} failed; no output file written\n", failed,
                           failed == 1 ? "" : "s");
}

int run_campaign(const CampaignArgs& a) {
  require_html_reports_for(a.report);
  TerminalProgress progress(a.quiet);
  const gyro::CampaignResult r = io::run_campaign_file(a.file, nullptr, &progress).result;
  progress.finish();
  const std::string out = a.json ? report::json_text(report::campaign_to_json(r))
                                 : report::campaign_text(r, report::AngleFormat(r.input.angle_unit));
  if (a.strict && !r.all_checks_pass()) {
    // A job that fails its checks is not filed: stdout still shows it, no file is written.
    if (a.output.empty() || a.output == "-") emit("", out);
    print_failed_checks(r.checks);
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
  std::string output;
  bool json = false, strict = false, quiet = false;
};

int run_orientations(const OrientationsArgs& a) {
  TerminalProgress progress(a.quiet);
  std::vector<std::filesystem::path> paths(a.files.begin(), a.files.end());
  const io::OrientationsJob job = io::run_orientation_files(paths, &progress);
  progress.finish();
  const report::AngleFormat f(job.orientations.front().result.input.angle_unit);
  const std::string out = a.json ? report::json_text(report::orientations_to_json(job.result))
                                 : report::orientations_text(job.result, f);
  if (a.strict && !job.result.all_checks_pass()) {
    if (a.output.empty() || a.output == "-") emit("", out);
    print_failed_checks(job.result.checks);
    return kInputError;
  }
  emit(a.output, out);
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

// The options of `gyro simulate`: the library's simulation settings, with
// angles and the noise model as the user types them.
struct SimulateArgs {
  std::string mode = "non-tracking";
  std::uint64_t seed = 1;
  std::string output;
  gyro::StationSimulation sim;
  double tau_arcsec = 600, latitude_deg = 34.2;
  double spin_momentum_Nms = 0, inertia_kgm2 = 0, torsion_Nm_per_rad = 0;
  std::vector<std::string> clamps{"0"};
  std::string centre = "0 12 34", noise = "white";
  double sigma_tracking_arcsec = 0;
  std::optional<double> sigma_initial_arcsec;  // σ_2 of Markov tracking noise; default σ_1
  bool quiet = false;
  std::vector<std::string> given;  // long names of the options typed (refused where unused)
};

// An option typed for a mode that does not use it is an error, not silently dropped (a trial
// found --tracking-reversals 20 ignored by --mode campaign but recorded in the file's header).
void refuse_unused(const SimulateArgs& a, std::initializer_list<const char*> unused,
                   const char* why) {
  for (const std::string& g : a.given)
    for (const char* u : unused)
      if (g == u)
        throw InputError(fmt::format("not used by --mode {}: {}", a.mode, why),
                         {"", std::nullopt, "--" + g});
}

gyro::NoiseModel::Kind noise_kind(const std::string& name) {
  if (name == "white") return gyro::NoiseModel::White;
  if (name == "markov1") return gyro::NoiseModel::Markov1;
  if (name == "markov2") return gyro::NoiseModel::Markov2;
  throw InputError("unknown noise model \"" + name + "\" (expected white, markov1 or markov2)",
                   {"", std::nullopt, "--noise"});
}

std::string header_text(const std::string& command_line, const std::vector<std::string>& truth) {
  std::string h = "Simulated by: " + command_line + "\n";
  for (const auto& t : truth) h += t + "\n";
  return h;
}

int run_simulate(const SimulateArgs& a, const std::string& command_line) {
  const gyro::NoiseModel::Kind noise = noise_kind(a.noise);
  if (a.mode == "campaign") {
    // The campaign simulator draws white timing and reading noise only: refuse what it would
    // ignore (a user trial found --noise markov1 silently dropped).
    if (noise != gyro::NoiseModel::White)
      throw InputError("campaign mode simulates white noise only (--sigma-time-s, --sigma-reading-div)",
                       {"", std::nullopt, "--noise"});
    if (a.sigma_initial_arcsec)
      throw InputError("only Markov tracking noise has initial states: give it with --mode tracking and "
                       "--noise markov1 or markov2",
                       {"", std::nullopt, "--sigma-initial-arcsec"});
    for (const std::string& g : a.given)
      if (g != "mode" && g != "seed" && g != "sigma-time-s" && g != "sigma-reading-div" &&
          g != "noise" && g != "output" && g != "quiet")
        throw InputError(
            "not used by --mode campaign: it simulates the example campaign's set-up (docs/gyro-"
            "theodolite.md), varied only by --seed, --sigma-time-s and --sigma-reading-div; "
            "simulate other runs with --mode tracking or non-tracking",
            {"", std::nullopt, "--" + g});
    gyro::CampaignTruth truth = gyro::example_campaign_truth();
    truth.sigma_time_s = a.sim.sigma_time_s;
    truth.sigma_reading_div = a.sim.sigma_reading_div;
    const auto sim = gyro::simulate_campaign(truth, a.seed);
    emit(a.output, io::campaign_file_yaml(sim.input, header_text(command_line, sim.truth)));
    return kOk;
  }
  gyro::StationSimulation s = a.sim;
  if (a.mode == "non-tracking") s.mode = gyro::Mode::NonTracking;
  else if (a.mode == "tracking") s.mode = gyro::Mode::Tracking;
  else
    throw InputError("unknown mode \"" + a.mode + "\" (expected non-tracking, tracking or campaign)",
                     {"", std::nullopt, "--mode"});
  if (s.mode == gyro::Mode::Tracking)
    refuse_unused(a, {"levels", "crossings", "reversals"},
                  "it is a non-tracking option (timed graduations and reversal readings)");
  else
    refuse_unused(a, {"centre", "tracking-amplitude-div", "kappa", "tracking-reversals",
                      "sigma-tracking-arcsec"},
                  "it is a tracking option");
  s.scale_value_rad = units::arcsec_to_rad(a.tau_arcsec);
  s.latitude_rad = units::deg_to_rad(a.latitude_deg);
  if (a.spin_momentum_Nms > 0 || a.inertia_kgm2 > 0 || a.torsion_Nm_per_rad > 0)
    s.physics = gyro::PhysicalGyro{a.spin_momentum_Nms, a.inertia_kgm2, a.torsion_Nm_per_rad};
  s.noise = noise;
  if (a.clamps.empty()) throw InputError("give at least one clamp reading", {"", std::nullopt, "--clamp"});
  if (a.clamps.size() > 1 && s.mode != gyro::Mode::NonTracking)
    throw InputError("several clamp readings are for non-tracking runs", {"", std::nullopt, "--clamp"});
  if (a.clamps.size() > static_cast<std::size_t>(s.determinations))
    throw InputError(fmt::format("{} clamp readings for {} determination(s): give --determinations {} or more",
                                 a.clamps.size(), s.determinations, a.clamps.size()),
                     {"", std::nullopt, "--clamp"});
  try {
    s.clamp_rad = parse_angle(a.clamps.front()).normalized_positive().rad();
    for (std::size_t i = 1; i < a.clamps.size(); ++i)
      s.other_clamps_rad.push_back(parse_angle(a.clamps[i]).normalized_positive().rad());
  } catch (Error& e) {
    e.add_context("", std::nullopt, "--clamp");
    throw;
  }
  s.centre_rad = parse_angle(a.centre).rad();
  s.sigma_tracking_rad = units::arcsec_to_rad(a.sigma_tracking_arcsec);
  if (a.sigma_initial_arcsec) {
    if (s.mode != gyro::Mode::Tracking || s.noise == gyro::NoiseModel::White)
      throw InputError("only Markov tracking noise has initial states: give it with --mode tracking and "
                       "--noise markov1 or markov2",
                       {"", std::nullopt, "--sigma-initial-arcsec"});
    if (!(*a.sigma_initial_arcsec >= 0) || !std::isfinite(*a.sigma_initial_arcsec))
      throw InputError("must be a finite value >= 0", {"", std::nullopt, "--sigma-initial-arcsec"});
    s.sigma_initial_tracking_rad = units::arcsec_to_rad(*a.sigma_initial_arcsec);
  }
  TerminalProgress progress(a.quiet);
  const gyro::SimulatedStation sim = gyro::simulate_station(s, a.seed, &progress);
  progress.finish();
  emit(a.output, io::reduce_file_yaml(sim.input, header_text(command_line, sim.truth)));
  return kOk;
}

}  // namespace
}  // namespace gyro_cmd

void add_gyro_commands(CLI::App& app, int& exit_code) {
  using namespace gyro_cmd;  // the command's option structs and run functions
  CLI::App* gyro = app.add_subcommand("gyro", "Gyro-theodolite orientation");
  gyro->require_subcommand(1);

  auto ra = std::make_shared<ReduceArgs>();
  CLI::App* reduce = gyro->add_subcommand("reduce", "Reduce the determinations in a YAML/JSON file to N_G");
  reduce->add_option("FILE", ra->file, "Input file (YAML, or JSON as is)")->required();
  reduce->add_flag("--json", ra->json, "Print one JSON object instead of text");
  reduce->add_option("-o,--output", ra->output, "Write to this file (atomically) instead of stdout");
  reduce->add_option("--report", ra->report, "Also write a self-contained HTML report (plots, tables) to this file");
  reduce->add_flag("-q,--quiet", ra->quiet, "No progress bar");
  reduce->callback([ra, &exit_code] { exit_code = guarded([&] { return run_reduce(*ra); }); });

  auto ca = std::make_shared<CampaignArgs>();
  CLI::App* camp = gyro->add_subcommand("campaign", "Process a whole station campaign to grid azimuths");
  camp->add_option("FILE", ca->file, "Campaign file (YAML or JSON)")->required();
  camp->add_flag("--json", ca->json, "Print JSON instead of text");
  camp->add_flag("--strict", ca->strict,
                 "When a tolerance check fails: list the failed checks on stderr, write no output file, exit 1");
  camp->add_option("-o,--output", ca->output, "Write to this file (atomically) instead of stdout");
  camp->add_option("--report", ca->report, "Also write a self-contained HTML report (plots, tables) to this file");
  camp->add_flag("-q,--quiet", ca->quiet, "No progress bar");
  camp->callback([ca, &exit_code] { exit_code = guarded([&] { return run_campaign(*ca); }); });

  auto tp = std::make_shared<TemplateArgs>();
  CLI::App* tmpl = gyro->add_subcommand("template", "Write a commented field book to start from");
  tmpl->add_option("--kind", tp->kind, "campaign (a whole 3-2-3 job) | reduce (the runs of one station)")
      ->capture_default_str();
  tmpl->add_option("-o,--output", tp->output, "Write to this file (atomically) instead of stdout");
  tmpl->callback([tp, &exit_code] { exit_code = guarded([&] { return run_template(*tp); }); });

  auto oa = std::make_shared<OrientationsArgs>();
  CLI::App* ori = gyro->add_subcommand(
      "orientations", "Two or more independent orientations of one line (campaign files): difference and mean");
  ori->add_option("FILES", oa->files, "Campaign files, one per independent orientation")->required()->expected(2, -1);
  ori->add_flag("--json", oa->json, "Print JSON instead of text");
  ori->add_flag("--strict", oa->strict, "Exit with code 1 when a check fails (and write nothing)");
  ori->add_option("-o,--output", oa->output, "Write to this file (atomically) instead of stdout");
  ori->add_flag("-q,--quiet", oa->quiet, "No progress bar");
  ori->callback([oa, &exit_code] { exit_code = guarded([&] { return run_orientations(*oa); }); });

  auto ta = std::make_shared<TransitArgs>();
  CLI::App* tf = gyro->add_subcommand(
      "transit-factor", "Empirical transit factor c from two transit determinations (east/west clamp)");
  tf->add_option("FILE", ta->file, "Reduce-format file with exactly two non-tracking determinations")->required();
  tf->add_flag("--json", ta->json, "Print JSON");
  tf->callback([ta, &exit_code] { exit_code = guarded([&] { return run_transit_factor(*ta); }); });

  auto sa = std::make_shared<SimulateArgs>();
  CLI::App* sim = gyro->add_subcommand("simulate", "Simulate observations (writes a reduce or campaign file)");
  sim->add_option("--mode", sa->mode, "non-tracking | tracking | campaign")->capture_default_str();
  sim->add_option("--seed", sa->seed, "Random seed (runs are reproducible)")->capture_default_str();
  sim->add_option("-o,--output", sa->output, "Output file (default stdout)");
  sim->add_option("--determinations", sa->sim.determinations, "Number of determinations (seeds seed, seed+1, ...)")->capture_default_str();
  sim->add_option("--tau-arcsec", sa->tau_arcsec, "Scale value tau (arcsec/div)")->capture_default_str();
  sim->add_option("--lambda", sa->sim.torsion_ratio, "Torsion ratio lambda at the station")->capture_default_str();
  sim->add_option("--latitude-deg", sa->latitude_deg, "Station latitude (deg)")->capture_default_str();
  sim->add_option("--spin-momentum-Nms", sa->spin_momentum_Nms, "H: derive periods and lambda from physics");
  sim->add_option("--inertia-kgm2", sa->inertia_kgm2, "J_z (with --spin-momentum-Nms)");
  sim->add_option("--torsion-Nm-per-rad", sa->torsion_Nm_per_rad, "D_B (with --spin-momentum-Nms)");
  sim->add_option("--beta-div", sa->sim.beta_div, "Non-tracking: equilibrium reading beta (div)")->capture_default_str();
  sim->add_option("--amplitude-div", sa->sim.amplitude_div, "Non-tracking: amplitude B (div)")->capture_default_str();
  sim->add_option("--period-s", sa->sim.period_s, "Non-tracking: period T_B (s)")->capture_default_str();
  sim->add_option("--t0-s", sa->sim.t0_s, "Non-tracking: eastward passage of beta (s)")->capture_default_str();
  sim->add_option("--damping-per-s", sa->sim.damping_per_s, "Non-tracking: damping k (1/s)")->capture_default_str();
  sim->add_option("--levels", sa->sim.levels_div, "Non-tracking: graduations to time (div)")->delimiter(',')->capture_default_str();
  sim->add_option("--crossings", sa->sim.crossings_per_level, "Non-tracking: crossings per level")->capture_default_str();
  sim->add_option("--reversals", sa->sim.reversals, "Non-tracking: reversal readings")->capture_default_str();
  sim->add_option("--clamp", sa->clamps,
                  "Non-tracking: clamp reading N' (DMS or deg); a comma-separated list clamps the determinations in "
                  "turn at the same gyro north (beta is for the first)")
      ->delimiter(',')
      ->capture_default_str();
  sim->add_option("--sigma-time-s", sa->sim.sigma_time_s, "Timing noise sigma (s)")->capture_default_str();
  sim->add_option("--sigma-reading-div", sa->sim.sigma_reading_div, "Scale reading noise sigma (div)")->capture_default_str();
  sim->add_flag("!--unknown-period", sa->sim.known_period, "Do not write period_s into the file");
  sim->add_option("--centre", sa->centre, "Tracking: centre M (DMS or deg)")->capture_default_str();
  sim->add_option("--tracking-amplitude-div", sa->sim.tracking_amplitude_div, "Tracking: amplitude A (div of tau)")->capture_default_str();
  sim->add_option("--kappa", sa->sim.kappa, "Tracking: decay per half period")->capture_default_str();
  sim->add_option("--tracking-reversals", sa->sim.tracking_reversals, "Tracking: number of reversals")->capture_default_str();
  sim->add_option("--sigma-tracking-arcsec", sa->sigma_tracking_arcsec, "Tracking: reading noise sigma (arcsec)")->capture_default_str();
  sim->add_option("--noise", sa->noise, "white | markov1 | markov2")->capture_default_str();
  sim->add_option("--sigma-initial-arcsec", sa->sigma_initial_arcsec,
                  "Tracking, Markov noise: sigma_2 of the initial state(s) X (arcsec; default: --sigma-tracking-arcsec)");
  sim->add_option("--rho1", sa->sim.rho1, "Markov coefficient rho1")->capture_default_str();
  sim->add_option("--rho2", sa->sim.rho2, "Markov-2 coefficient rho2")->capture_default_str();
  sim->add_flag("-q,--quiet", sa->quiet, "No progress bar");
  sim->callback([sa, sim, &exit_code] {
    std::string cmd = "meridian gyro simulate";
    // The options that shape the data, as they can be typed again.
    for (const CLI::Option* o : sim->get_options()) {
      if (o->count() == 0 || o->get_lnames().empty()) continue;
      const std::string name = o->get_lnames().front();
      if (name == "help" || name == "output" || name == "quiet") continue;
      cmd += " --" + name;
      if (o->get_expected_min() == 0) continue;
      std::string value;
      for (const auto& r : o->results()) value += (value.empty() ? "" : ",") + r;
      cmd += value.find(' ') == std::string::npos ? " " + value : " \"" + value + "\"";
    }
    sa->given.clear();
    for (const CLI::Option* o : sim->get_options())
      if (o->count() > 0 && !o->get_lnames().empty()) sa->given.push_back(o->get_lnames().front());
    exit_code = guarded([&] { return run_simulate(*sa, cmd); });
  });

  auto sto = std::make_shared<StochasticArgs>();
  CLI::App* stoch = gyro->add_subcommand(
      "stochastic", "Compare stochastic models (white noise, covariance functions, Markov-1/-2) of each reversal series");
  stoch->add_option("FILE", sto->file, "Field book as for gyro reduce, or a campaign file (YAML or JSON)")->required();
  stoch->add_flag("--json", sto->json, "Print JSON instead of text");
  stoch->add_option("-o,--output", sto->output, "Write to this file (atomically) instead of stdout");
  stoch->add_flag("-q,--quiet", sto->quiet, "No progress bar");
  stoch->add_option("--report", sto->report,
                    "Also write a self-contained HTML report (comparison table, autocorrelation, Markov-2 likelihood surface)");
  stoch->callback([sto, &exit_code] { exit_code = guarded([&] { return run_stochastic(*sto); }); });
}

}  // namespace meridian::cli
