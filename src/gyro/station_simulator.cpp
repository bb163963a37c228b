#include "meridian/gyro/station_simulator.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "meridian/core/dms.hpp"

namespace meridian::gyro {
namespace {

// sigma_initial: σ of the initial states X (σ_2); σ of Δ (σ_1) when not given.
NoiseModel noise_model(const StationSimulation& s, double sigma,
                       double sigma_initial = std::numeric_limits<double>::quiet_NaN()) {
  const double s2 = std::isnan(sigma_initial) ? sigma : sigma_initial;
  switch (s.noise) {
    case NoiseModel::Markov1: return NoiseModel::markov1(sigma, s.rho1, s2);
    case NoiseModel::Markov2: return NoiseModel::markov2(sigma, s.rho1, s.rho2, s2);
    case NoiseModel::White: break;
  }
  return NoiseModel::white(sigma);
}

// The noise model for the Truth line (empty for white noise, so white-noise headers are as
// before): the kind, ρ, and the σ of the initial states X (that of Δ unless one is given, in
// arcsec: only tracking noise takes one).
std::string noise_clause(const StationSimulation& s, bool tracking) {
  const bool own = tracking && !std::isnan(s.sigma_initial_tracking_rad);
  const std::string x =
      own ? fmt::format("{:g} arcsec", s.sigma_initial_tracking_rad / units::kArcsecond)
          : "sigma of Delta";
  switch (s.noise) {
    case NoiseModel::Markov1:
      return fmt::format("; noise markov1 (rho1 = {}), sigma of the initial state X0 = {}", s.rho1, x);
    case NoiseModel::Markov2:
      return fmt::format("; noise markov2 (rho1 = {}, rho2 = {}), sigma of the initial states X1, X2 = {}",
                         s.rho1, s.rho2, x);
    case NoiseModel::White: break;
  }
  return {};
}

std::string dms3(double rad) { return format_direction_dms(Angle::radians(rad), {3, true, false}); }

}  // namespace

SimulatedStation simulate_station(const StationSimulation& s, std::uint64_t seed, Progress* progress) {
  SimulatedStation out;
  InstrumentSpec& spec = out.input.instrument;
  spec.scale_value_rad = s.scale_value_rad;
  // Noise-free data still carry realistic weights.
  spec.sigma_time_s = s.sigma_time_s > 0 ? s.sigma_time_s : kDefaultSigmaTime_s;
  spec.sigma_reading_div = s.sigma_reading_div > 0 ? s.sigma_reading_div : kDefaultSigmaReading_div;
  out.input.latitude_rad = s.latitude_rad;
  double lambda = s.torsion_ratio, period = s.period_s;
  if (s.physics) {
    const GyroPeriods p = periods_from_physics(*s.physics, s.latitude_rad);
    lambda = p.torsion_ratio;
    period = p.nontracking_s;
    out.truth.push_back(fmt::format(
        "From physics at latitude {:.4f} deg: T_A = {:.3f} s, T_B = {:.3f} s, T_F = {:.3f} s, lambda = {:.5f}",
        units::rad_to_deg(s.latitude_rad), p.tracking_s, p.nontracking_s, p.free_s, p.torsion_ratio));
  }
  spec.torsion_ratio = Uncertain{lambda, 0.0};
  const Instrument inst = resolve_instrument(spec, s.latitude_rad).instrument;
  std::vector<double> clamps{s.clamp_rad};
  clamps.insert(clamps.end(), s.other_clamps_rad.begin(), s.other_clamps_rad.end());
  const double north_rad = north_from_nontracking(s.clamp_rad, Uncertain{s.beta_div, 0.0}, inst).north_rad;
  for (int i = 0; i < s.determinations; ++i) {
    report_progress(progress, static_cast<std::size_t>(i), static_cast<std::size_t>(s.determinations), "simulating");
    const std::uint64_t det_seed = seed + static_cast<std::uint64_t>(i);
    DeterminationInput d;
    d.mode = s.mode;
    if (s.mode == Mode::NonTracking) {
      d.clamp_reading_rad = clamps[static_cast<std::size_t>(i) % clamps.size()];
      NonTrackingSimulation n;
      n.beta_div = d.clamp_reading_rad == s.clamp_rad ? s.beta_div : beta_for_north(north_rad, d.clamp_reading_rad, inst);
      n.amplitude_div = s.amplitude_div;
      n.period_s = period;
      n.t0_s = s.t0_s;
      n.damping_per_s = s.damping_per_s;
      n.levels_div = s.levels_div;
      n.crossings_per_level = s.crossings_per_level;
      n.reversals = s.reversals;
      n.record_reversal_times = false;
      n.time_noise = noise_model(s, s.sigma_time_s);
      n.reading_noise = noise_model(s, s.sigma_reading_div);
      if (s.known_period) n.known_period_s = period;
      n.reported_sigma_time_s = spec.sigma_time_s;
      n.reported_sigma_reading_div = spec.sigma_reading_div;
      d.nontracking = simulate_nontracking(n, det_seed);
      if (i == 0) {
        const NorthReading north = north_from_nontracking(d.clamp_reading_rad, Uncertain{s.beta_div, 0.0}, inst);
        out.truth.push_back(fmt::format("Truth: beta = {} div, N_G = {} (delta N = {:+.3f}\"), B = "
                                        "{} div, T_B = {} s, t0 = {} s, k = {} 1/s",
                                        s.beta_div, dms3(north.north_rad),
                                        north.delta_n_rad / units::kArcsecond, s.amplitude_div,
                                        period, s.t0_s, s.damping_per_s) +
                            noise_clause(s, false));
        if (clamps.size() > 1) {
          std::string list;
          for (double c : clamps)
            list += fmt::format("{}{} (beta {:.5f} div)", list.empty() ? "" : ", ", dms3(c),
                                c == s.clamp_rad ? s.beta_div : beta_for_north(north_rad, c, inst));
          out.truth.push_back("Clamps in turn: " + list);
        }
      }
    } else {
      TrackingSimulation t;
      t.centre_rad = s.centre_rad;
      t.amplitude_rad = s.tracking_amplitude_div * inst.scale_value_rad;
      t.kappa = s.kappa;
      t.reversals = s.tracking_reversals;
      t.reading_noise = noise_model(s, s.sigma_tracking_rad, s.sigma_initial_tracking_rad);
      d.tracking.reversals_rad = simulate_tracking(t, det_seed);
      if (s.sigma_tracking_rad > 0) d.tracking.sigma_reading_rad = s.sigma_tracking_rad;
      if (i == 0)
        out.truth.push_back(fmt::format("Truth: M = {} (= N_G without zero-position correction), A = {} div, kappa = {}",
                                        dms3(t.centre_rad), s.tracking_amplitude_div, s.kappa) +
                                noise_clause(s, true));
    }
    out.input.determinations.push_back(std::move(d));
  }
  return out;
}

}  // namespace meridian::gyro
