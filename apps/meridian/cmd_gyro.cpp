// meridian gyro reduce | campaign | simulate | transit-factor

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "commands.hpp"
#include "gyro_runs.hpp"
#include "meridian/core/dms.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gyro/campaign.hpp"
#include "meridian/gyro/campaign_simulator.hpp"
#include "meridian/gyro/instrument_spec.hpp"
#include "meridian/gyro/simulator.hpp"
#include "meridian/gyro/transit_calibration.hpp"
#include "meridian/io/gyro_files.hpp"
#include "meridian/io/gyro_writers.hpp"
#include "meridian/report/gyro_html.hpp"
#include "meridian/report/gyro_json.hpp"
#include "meridian/report/gyro_text.hpp"
#include "meridian/report/html.hpp"

namespace meridian::cli {
namespace {

constexpr double kArcsec = units::kArcsecond;

struct ReduceArgs {
  std::string file, output, report;
  bool json = false, quiet = false;
};

int run_reduce(const ReduceArgs& a) {
  TerminalProgress progress(a.quiet);
  const ReducedFile reduced = reduce_file(a.file, &progress);
  const io::GyroReduceFile& f = reduced.file;
  const gyro::ResolvedInstrument& inst = reduced.instrument;
  const std::vector<gyro::DeterminationResult>& results = reduced.results;
  std::string out;
  if (a.json) {
    nlohmann::json j;
    j["file"] = f.file;
    j["torsion_ratio"] = {{"value", inst.instrument.torsion_ratio.value},
                          {"sigma", inst.instrument.torsion_ratio.sigma}};
    j["notes"] = inst.notes;
    j["determinations"] = nlohmann::json::array();
    for (const auto& r : results) j["determinations"].push_back(report::determination_to_json(r));
    out = j.dump(2) + "\n";
  } else {
    out = fmt::format("{}: {} determination(s), lambda = {:.5f}, tau = {:.1f}\"/div\n", f.file,
                      results.size(), inst.instrument.torsion_ratio.value,
                      inst.instrument.scale_value_rad / kArcsec);
    for (const auto& n : inst.notes) out += "  note: " + n + "\n";
    for (std::size_t i = 0; i < results.size(); ++i) out += report::determination_text(results[i], static_cast<int>(i));
  }
  progress.finish();
  // Everything is computed before anything is written.
  const std::string html = a.report.empty() ? std::string()
                                            : report::render_html(report::gyro_reduce_document(
                                                  f.file, inst, f.latitude_rad, f.determinations, results));
  emit(a.output, out);
  if (!a.report.empty()) emit(a.report, html);
  return kOk;
}

struct CampaignArgs {
  std::string file, output, report;
  bool json = false, strict = false, quiet = false;
};

int run_campaign(const CampaignArgs& a) {
  const io::CampaignFile f = io::read_campaign_file(a.file);
  TerminalProgress progress(a.quiet);
  const gyro::CampaignResult r = process_campaign_file(f, &progress);
  progress.finish();
  const std::string out = a.json ? report::campaign_to_json(r).dump(2) + "\n" : report::campaign_text(r);
  const std::string html = a.report.empty() ? std::string()
                                            : report::render_html(report::gyro_campaign_document(f.file, f.campaign, r));
  emit(a.output, out);
  if (!a.report.empty()) emit(a.report, html);
  return (a.strict && !r.all_checks_pass()) ? kInputError : kOk;
}

struct TransitArgs {
  std::string file;
  bool json = false;
};

int run_transit_factor(const TransitArgs& a) {
  const io::GyroReduceFile f = io::read_gyro_reduce_file(a.file);
  if (f.determinations.size() != 2)
    throw InputError(fmt::format("exactly two determinations (east and west clamp) are needed, got {}",
                                 f.determinations.size()),
                     {f.file, std::nullopt, "determinations"});
  const auto inst = gyro::resolve_instrument(f.instrument, f.latitude_rad);
  gyro::TransitFactorCalibration c;
  try {
    c = gyro::calibrate_transit_factor(f.determinations[0], f.determinations[1], inst.instrument);
  } catch (Error& e) {
    io::locate_error(e, f.file, f.lines);
    throw;
  }
  std::string out;
  if (a.json) {
    nlohmann::json j = {{"transit_factor_arcsec_per_div_s", c.factor_rad_per_div_s.value / kArcsec},
                        {"sigma_arcsec_per_div_s", c.factor_rad_per_div_s.sigma / kArcsec},
                        {"computed_arcsec_per_div_s", c.computed_rad_per_div_s / kArcsec},
                        {"amplitudes_div", {c.amplitude1_div.value, c.amplitude2_div.value}},
                        {"time_differences_s", {c.dt1_s.value, c.dt2_s.value}},
                        {"north_reading_deg", c.north_rad / units::kDegree},
                        {"notes", c.notes}};
    out = j.dump(2) + "\n";
  } else {
    out = fmt::format("transit factor c = {:.4f} \"/(div s)  sigma {:.4f}\n", c.factor_rad_per_div_s.value / kArcsec,
                      c.factor_rad_per_div_s.sigma / kArcsec);
    if (c.computed_rad_per_div_s > 0)
      out += fmt::format("computed (1+lambda) tau pi/(2 T_B) = {:.4f} \"/(div s)\n", c.computed_rad_per_div_s / kArcsec);
    out += fmt::format("B1 = {:.3f} div, dt1 = {:+.3f} s; B2 = {:.3f} div, dt2 = {:+.3f} s\n", c.amplitude1_div.value,
                       c.dt1_s.value, c.amplitude2_div.value, c.dt2_s.value);
    out += "gyro north N = " + format_direction_dms(Angle::radians(c.north_rad)) + "\n";
    for (const auto& n : c.notes) out += "note: " + n + "\n";
  }
  emit("", out);
  return kOk;
}

struct SimulateArgs {
  std::string mode = "non-tracking";
  std::uint64_t seed = 1;
  std::string output;
  // Instrument
  double tau_arcsec = 600, lambda = 0.30, latitude_deg = 34.2;
  // Physical description (optional)
  double spin_momentum_Nms = 0, inertia_kgm2 = 0, torsion_Nm_per_rad = 0;
  // Non-tracking truth
  double beta_div = -0.12, amplitude_div = 9, period_s = 440, t0_s = 50, damping_per_s = 0;
  std::vector<double> levels{-2.0, 0.0, 2.0};
  int crossings = 3, reversals = 2;
  std::string clamp = "0";
  double sigma_time_s = 0.1, sigma_reading_div = 0.05;
  bool known_period = true;
  // Tracking truth
  std::string centre = "0 12 34";
  double tracking_amplitude_div = 8, kappa = 0.002, sigma_tracking_arcsec = 0;
  int tracking_reversals = 5;
  std::string noise = "white";
  double rho1 = 0.5, rho2 = 0.0;
  int determinations = 1;
  bool quiet = false;
};

gyro::NoiseModel noise_model(const SimulateArgs& a, double sigma) {
  if (a.noise == "white") return gyro::NoiseModel::white(sigma);
  if (a.noise == "markov1") return gyro::NoiseModel::markov1(sigma, a.rho1, sigma);
  if (a.noise == "markov2") return gyro::NoiseModel::markov2(sigma, a.rho1, a.rho2, sigma);
  throw InputError("unknown noise model \"" + a.noise + "\" (expected white, markov1 or markov2)",
                   {"", std::nullopt, "--noise"});
}

int run_simulate(const SimulateArgs& a, const std::string& command_line) {
  std::string header = "Simulated by: " + command_line + "\n";
  if (a.mode == "campaign") {
    gyro::CampaignTruth truth = gyro::example_campaign_truth();
    truth.sigma_time_s = a.sigma_time_s;
    truth.sigma_reading_div = a.sigma_reading_div;
    const auto sim = gyro::simulate_campaign(truth, a.seed);
    header += fmt::format("Truth: grid azimuth C-D {} ; known line A-B grid azimuth {} ; E = {:+.1f}\"\n",
                          format_direction_dms(Angle::radians(sim.true_grid_azimuth_rad), {3, true, false}),
                          format_direction_dms(Angle::radians(sim.true_known_grid_azimuth_rad), {3, true, false}),
                          truth.instrument_constant_rad / kArcsec);
    emit(a.output, io::campaign_file_yaml(sim.input, header));
    return kOk;
  }
  gyro::InstrumentSpec spec;
  spec.scale_value_rad = a.tau_arcsec * kArcsec;
  spec.sigma_time_s = a.sigma_time_s > 0 ? a.sigma_time_s : 0.1;
  spec.sigma_reading_div = a.sigma_reading_div > 0 ? a.sigma_reading_div : 0.05;
  const double lat = units::deg_to_rad(a.latitude_deg);
  double lambda = a.lambda, period = a.period_s;
  const bool physical = a.spin_momentum_Nms > 0 || a.inertia_kgm2 > 0 || a.torsion_Nm_per_rad > 0;
  if (physical) {
    const gyro::PhysicalGyro g{a.spin_momentum_Nms, a.inertia_kgm2, a.torsion_Nm_per_rad};
    const gyro::GyroPeriods p = gyro::periods_from_physics(g, lat);
    lambda = p.torsion_ratio;
    period = p.nontracking_s;
    header += fmt::format("From physics at latitude {:.4f} deg: T_A = {:.3f} s, T_B = {:.3f} s, T_F = {:.3f} s, lambda = {:.5f}\n",
                          a.latitude_deg, p.tracking_s, p.nontracking_s, p.free_s, p.torsion_ratio);
  }
  spec.torsion_ratio = gyro::Uncertain{lambda, 0.0};
  const gyro::Instrument inst = gyro::resolve_instrument(spec, lat).instrument;
  std::vector<gyro::DeterminationInput> dets;
  TerminalProgress progress(a.quiet);
  for (int i = 0; i < a.determinations; ++i) {
    progress.update(static_cast<std::size_t>(i), static_cast<std::size_t>(a.determinations), "simulating");
    const std::uint64_t seed = a.seed + static_cast<std::uint64_t>(i);
    gyro::DeterminationInput d;
    d.method = "all";
    if (a.mode == "non-tracking") {
      d.mode = gyro::Mode::NonTracking;
      d.clamp_reading_rad = parse_angle(a.clamp).normalized_positive().rad();
      gyro::NonTrackingSimulation s;
      s.beta_div = a.beta_div;
      s.amplitude_div = a.amplitude_div;
      s.period_s = period;
      s.t0_s = a.t0_s;
      s.damping_per_s = a.damping_per_s;
      s.levels_div = a.levels;
      s.crossings_per_level = a.crossings;
      s.reversals = a.reversals;
      s.record_reversal_times = false;
      s.time_noise = noise_model(a, a.sigma_time_s);
      s.reading_noise = noise_model(a, a.sigma_reading_div);
      if (a.known_period) s.known_period_s = period;
      s.reported_sigma_time_s = spec.sigma_time_s;
      s.reported_sigma_reading_div = spec.sigma_reading_div;
      d.nontracking = gyro::simulate_nontracking(s, seed);
      const double north = d.clamp_reading_rad + (1.0 + inst.torsion_ratio.value) * inst.scale_value_rad * a.beta_div;
      if (i == 0)
        header += fmt::format("Truth: beta = {} div, N_G = {} (delta N = {:+.3f}\"), B = {} div, T_B = {} s, t0 = {} s, k = {} 1/s\n",
                              a.beta_div, format_direction_dms(Angle::radians(north), {3, true, false}),
                              (north - d.clamp_reading_rad) / kArcsec, a.amplitude_div, period, a.t0_s, a.damping_per_s);
    } else if (a.mode == "tracking") {
      d.mode = gyro::Mode::Tracking;
      gyro::TrackingSimulation s;
      s.centre_rad = parse_angle(a.centre).rad();
      s.amplitude_rad = a.tracking_amplitude_div * inst.scale_value_rad;
      s.kappa = a.kappa;
      s.reversals = a.tracking_reversals;
      s.reading_noise = noise_model(a, a.sigma_tracking_arcsec * kArcsec);
      d.tracking.reversals_rad = gyro::simulate_tracking(s, seed);
      if (a.sigma_tracking_arcsec > 0) d.tracking.sigma_reading_rad = a.sigma_tracking_arcsec * kArcsec;
      if (i == 0)
        header += fmt::format("Truth: M = {} (= N_G without zero-position correction), A = {} div, kappa = {}\n",
                              format_direction_dms(Angle::radians(s.centre_rad), {3, true, false}),
                              a.tracking_amplitude_div, a.kappa);
    } else {
      throw InputError("unknown mode \"" + a.mode + "\" (expected non-tracking, tracking or campaign)",
                       {"", std::nullopt, "--mode"});
    }
    dets.push_back(std::move(d));
  }
  progress.finish();
  emit(a.output, io::reduce_file_yaml(spec, lat, dets, header));
  return kOk;
}

}  // namespace

void add_gyro_commands(CLI::App& app, int& exit_code) {
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
  camp->add_flag("--strict", ca->strict, "Exit with code 1 when a tolerance check fails");
  camp->add_option("-o,--output", ca->output, "Write to this file (atomically) instead of stdout");
  camp->add_option("--report", ca->report, "Also write a self-contained HTML report (plots, tables) to this file");
  camp->add_flag("-q,--quiet", ca->quiet, "No progress bar");
  camp->callback([ca, &exit_code] { exit_code = guarded([&] { return run_campaign(*ca); }); });

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
  sim->add_option("--determinations", sa->determinations, "Number of determinations (seeds seed, seed+1, ...)")->capture_default_str();
  sim->add_option("--tau-arcsec", sa->tau_arcsec, "Scale value tau (arcsec/div)")->capture_default_str();
  sim->add_option("--lambda", sa->lambda, "Torsion ratio lambda at the station")->capture_default_str();
  sim->add_option("--latitude-deg", sa->latitude_deg, "Station latitude (deg)")->capture_default_str();
  sim->add_option("--spin-momentum-Nms", sa->spin_momentum_Nms, "H: derive periods and lambda from physics");
  sim->add_option("--inertia-kgm2", sa->inertia_kgm2, "J_z (with --spin-momentum-Nms)");
  sim->add_option("--torsion-Nm-per-rad", sa->torsion_Nm_per_rad, "D_B (with --spin-momentum-Nms)");
  sim->add_option("--beta-div", sa->beta_div, "Non-tracking: equilibrium reading beta (div)")->capture_default_str();
  sim->add_option("--amplitude-div", sa->amplitude_div, "Non-tracking: amplitude B (div)")->capture_default_str();
  sim->add_option("--period-s", sa->period_s, "Non-tracking: period T_B (s)")->capture_default_str();
  sim->add_option("--t0-s", sa->t0_s, "Non-tracking: eastward passage of beta (s)")->capture_default_str();
  sim->add_option("--damping-per-s", sa->damping_per_s, "Non-tracking: damping k (1/s)")->capture_default_str();
  sim->add_option("--levels", sa->levels, "Non-tracking: graduations to time (div)")->delimiter(',')->capture_default_str();
  sim->add_option("--crossings", sa->crossings, "Non-tracking: crossings per level")->capture_default_str();
  sim->add_option("--reversals", sa->reversals, "Non-tracking: reversal readings")->capture_default_str();
  sim->add_option("--clamp", sa->clamp, "Non-tracking: clamp reading N' (DMS or deg)")->capture_default_str();
  sim->add_option("--sigma-time-s", sa->sigma_time_s, "Timing noise sigma (s)")->capture_default_str();
  sim->add_option("--sigma-reading-div", sa->sigma_reading_div, "Scale reading noise sigma (div)")->capture_default_str();
  sim->add_flag("!--unknown-period", sa->known_period, "Do not write period_s into the file");
  sim->add_option("--centre", sa->centre, "Tracking: centre M (DMS or deg)")->capture_default_str();
  sim->add_option("--tracking-amplitude-div", sa->tracking_amplitude_div, "Tracking: amplitude A (div of tau)")->capture_default_str();
  sim->add_option("--kappa", sa->kappa, "Tracking: decay per half period")->capture_default_str();
  sim->add_option("--tracking-reversals", sa->tracking_reversals, "Tracking: number of reversals")->capture_default_str();
  sim->add_option("--sigma-tracking-arcsec", sa->sigma_tracking_arcsec, "Tracking: reading noise sigma (arcsec)")->capture_default_str();
  sim->add_option("--noise", sa->noise, "white | markov1 | markov2")->capture_default_str();
  sim->add_option("--rho1", sa->rho1, "Markov coefficient rho1")->capture_default_str();
  sim->add_option("--rho2", sa->rho2, "Markov-2 coefficient rho2")->capture_default_str();
  sim->add_flag("-q,--quiet", sa->quiet, "No progress bar");
  sim->callback([sa, sim, &exit_code] {
    std::string cmd = "meridian gyro simulate";
    for (const CLI::Option* o : sim->get_options())
      if (o->count() > 0 && o->get_name() != "--help" && o->get_name() != "-o,--output" &&
          o->get_name() != "-q,--quiet" && !o->get_lnames().empty()) {
        cmd += " --" + o->get_lnames().front();
        if (o->get_expected_min() > 0)
          for (const auto& r : o->results()) cmd += " " + r;
      }
    exit_code = guarded([&] { return run_simulate(*sa, cmd); });
  });
}

}  // namespace meridian::cli
