#include "meridian/io/gyro_simulate.hpp"

#include <cmath>
#include <initializer_list>
#include <utility>

#include <fmt/format.h>

#include "meridian/core/dms.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"

namespace meridian::io {
namespace {

InputError option_error(const std::string& message, const std::string& option) {
  return InputError(message, {"", std::nullopt, option});
}

// An option given for a mode that does not use it is an error, not silently dropped (a trial
// found --tracking-reversals 20 ignored by --mode campaign but recorded in the file's header).
void refuse_unused(const SimulateSettings& s, std::initializer_list<const char*> unused, const char* why) {
  for (const std::string& g : s.given)
    for (const char* u : unused)
      if (g == u) throw option_error(fmt::format("not used by --mode {}: {}", s.mode, why), "--" + g);
}

gyro::NoiseModel::Kind noise_kind(const std::string& name) {
  if (name == "white") return gyro::NoiseModel::White;
  if (name == "markov1") return gyro::NoiseModel::Markov1;
  if (name == "markov2") return gyro::NoiseModel::Markov2;
  throw option_error("unknown noise model \"" + name + "\" (expected white, markov1 or markov2)", "--noise");
}

const char* const kInitialStatesOnlyMarkovTracking =
    "only Markov tracking noise has initial states: give it with --mode tracking and "
    "--noise markov1 or markov2";

// The campaign mode: the example campaign's set-up, varied only by the seed and the white σ.
gyro::CampaignTruth campaign_truth(const SimulateSettings& s, gyro::NoiseModel::Kind noise) {
  // The campaign simulator draws white timing and reading noise only: refuse what it would
  // ignore (a user trial found --noise markov1 silently dropped).
  if (noise != gyro::NoiseModel::White)
    throw option_error("campaign mode simulates white noise only (--sigma-time-s, --sigma-reading-div)", "--noise");
  if (s.sigma_initial_arcsec) throw option_error(kInitialStatesOnlyMarkovTracking, "--sigma-initial-arcsec");
  for (const std::string& g : s.given)
    if (g != "mode" && g != "seed" && g != "sigma-time-s" && g != "sigma-reading-div" && g != "noise" &&
        g != "output" && g != "quiet")
      throw option_error(
          "not used by --mode campaign: it simulates the example campaign's set-up (docs/gyro-"
          "theodolite.md), varied only by --seed, --sigma-time-s and --sigma-reading-div; "
          "simulate other runs with --mode tracking or non-tracking",
          "--" + g);
  gyro::CampaignTruth truth = gyro::example_campaign_truth();
  truth.sigma_time_s = s.sim.sigma_time_s;
  truth.sigma_reading_div = s.sim.sigma_reading_div;
  return truth;
}

// The clamp readings N′ of the determinations in turn.
void read_clamps(const SimulateSettings& s, gyro::StationSimulation& out) {
  if (s.clamps.empty()) throw option_error("give at least one clamp reading", "--clamp");
  if (s.clamps.size() > 1 && out.mode != gyro::Mode::NonTracking)
    throw option_error("several clamp readings are for non-tracking runs", "--clamp");
  if (s.clamps.size() > static_cast<std::size_t>(out.determinations))
    throw option_error(fmt::format("{} clamp readings for {} determination(s): give --determinations {} or more",
                                   s.clamps.size(), out.determinations, s.clamps.size()),
                       "--clamp");
  try {
    out.clamp_rad = parse_angle(s.clamps.front()).normalized_positive().rad();
    for (std::size_t i = 1; i < s.clamps.size(); ++i)
      out.other_clamps_rad.push_back(parse_angle(s.clamps[i]).normalized_positive().rad());
  } catch (Error& e) {
    e.add_context("", std::nullopt, "--clamp");
    throw;
  }
}

// The non-tracking and tracking modes: one station's runs.
gyro::StationSimulation station_simulation(const SimulateSettings& s, gyro::NoiseModel::Kind noise) {
  gyro::StationSimulation out = s.sim;
  if (s.mode == "non-tracking") out.mode = gyro::Mode::NonTracking;
  else if (s.mode == "tracking") out.mode = gyro::Mode::Tracking;
  else throw option_error("unknown mode \"" + s.mode + "\" (expected non-tracking, tracking or campaign)", "--mode");
  if (out.mode == gyro::Mode::Tracking)
    refuse_unused(s, {"levels", "crossings", "reversals"},
                  "it is a non-tracking option (timed graduations and reversal readings)");
  else
    refuse_unused(s, {"centre", "tracking-amplitude-div", "kappa", "tracking-reversals", "sigma-tracking-arcsec"},
                  "it is a tracking option");
  out.scale_value_rad = units::arcsec_to_rad(s.tau_arcsec);
  out.latitude_rad = units::deg_to_rad(s.latitude_deg);
  if (s.spin_momentum_Nms > 0 || s.inertia_kgm2 > 0 || s.torsion_Nm_per_rad > 0)
    out.physics = gyro::PhysicalGyro{s.spin_momentum_Nms, s.inertia_kgm2, s.torsion_Nm_per_rad};
  out.noise = noise;
  read_clamps(s, out);
  out.centre_rad = parse_angle(s.centre).rad();
  out.sigma_tracking_rad = units::arcsec_to_rad(s.sigma_tracking_arcsec);
  if (s.sigma_initial_arcsec) {
    if (out.mode != gyro::Mode::Tracking || out.noise == gyro::NoiseModel::White)
      throw option_error(kInitialStatesOnlyMarkovTracking, "--sigma-initial-arcsec");
    if (!(*s.sigma_initial_arcsec >= 0) || !std::isfinite(*s.sigma_initial_arcsec))
      throw option_error("must be a finite value >= 0", "--sigma-initial-arcsec");
    out.sigma_initial_tracking_rad = units::arcsec_to_rad(*s.sigma_initial_arcsec);
  }
  return out;
}

}  // namespace

SimulationInput read_simulate_settings(const SimulateSettings& s) {
  const gyro::NoiseModel::Kind noise = noise_kind(s.noise);
  SimulationInput in;
  in.seed = s.seed;
  in.command_line = s.command_line;
  if (s.mode == "campaign") in.what = campaign_truth(s, noise);
  else in.what = station_simulation(s, noise);
  return in;
}

SimulatedBook run_simulation(const SimulationInput& in, Progress* progress) {
  SimulatedBook out;
  out.command_line = in.command_line;
  if (const auto* truth = std::get_if<gyro::CampaignTruth>(&in.what))
    out.book = gyro::simulate_campaign(*truth, in.seed);
  else
    out.book = gyro::simulate_station(std::get<gyro::StationSimulation>(in.what), in.seed, progress);
  return out;
}

SimulatedBook run_simulation(const SimulateSettings& settings, Progress* progress) {
  return run_simulation(read_simulate_settings(settings), progress);
}

}  // namespace meridian::io
