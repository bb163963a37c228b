#include "meridian/gyro/campaign_simulator.hpp"

#include <cmath>
#include <random>

#include <fmt/format.h>

#include "meridian/core/angle.hpp"
#include "meridian/core/dms.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/geodesy/azimuth_chain.hpp"
#include "meridian/geodesy/sight.hpp"
#include "meridian/gyro/simulator.hpp"

namespace meridian::gyro {
namespace {

constexpr double kArcmin = units::kArcminute;

struct Station {
  PointResult point;
  Instrument inst;
  double period_s;
};

// The truth is defined by grid coordinates (the chord azimuths come from them).
PointResult locate(const PointInput& p, const geodesy::TransverseMercatorGrid& grid, const char* what) {
  if (!p.x_north_m || !p.y_east_m)
    throw InputError(fmt::format("the simulator needs grid coordinates for the {}", what));
  std::vector<std::string> unused;
  return resolve_point(p, grid, what, unused);
}

// Round to the printed precision so the file written holds exactly the
// values used: times to 1 ms, readings to 0.01 div, angles to 0.1".
// Dividing by the whole number 1/q gives the double nearest the decimal
// (479.203, not 479.20300000000003).
double round_to(double v, double q) {
  if (q < 1.0) {
    const double inv = std::round(1.0 / q);
    return std::round(v * inv) / inv;
  }
  return std::round(v / q) * q;
}

// round_to, or nothing when the truth asks for exact observations.
struct Rounder {
  bool on;
  double operator()(double v, double q) const { return on ? round_to(v, q) : v; }
};

// One determination aimed so that r_target − N_G = A_G.
DeterminationInput simulate_determination(const CampaignTruth& t, const Station& st, double gyro_az,
                                          bool tracking, const std::string& label,
                                          std::mt19937_64& rng) {
  const Rounder rnd{t.round_to_field_precision};
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  DeterminationInput d;
  d.label = label;
  // The surveyor points at the target with some arbitrary circle orientation.
  const double r_target_true = wrap_positive_rad((180.0 + 170.0 * uni(rng)) * units::kDegree);
  const double north = wrap_positive_rad(r_target_true - gyro_az);
  const double pointing_noise = t.sigma_pointing_arcsec * units::kArcsecond * normal(rng);
  d.target_reading_rad =
      Uncertain{wrap_positive_rad(rnd(r_target_true + pointing_noise, 0.1 * units::kArcsecond)),
                (t.sigma_pointing_arcsec > 0 ? t.sigma_pointing_arcsec : 1.0) * units::kArcsecond};

  // Zero position before and after (motor off), drifting slightly.
  const double zp_before = t.alpha_p_div;
  const double zp_after = t.alpha_p_div + t.alpha_p_drift_div;
  const NoiseModel zn = NoiseModel::white(t.sigma_reading_div);
  auto zero_run = [&](double ap) {
    ZeroPositionRun run;
    for (double v : simulate_zero_position(ap, 6.0 + uni(rng), 0.01, 5, zn, rng()))
      run.reversals_div.push_back(rnd(v, 0.01));
    return run;
  };
  d.zero_before = zero_run(zp_before);
  d.zero_after = zero_run(zp_after);
  const double ap = 0.5 * (zp_before + zp_after);  // what the reduction will use

  if (tracking) {
    d.mode = Mode::Tracking;
    TrackingSimulation s;
    s.centre_rad = tracking_centre_for_north(north, st.inst, ap);
    s.amplitude_rad = 8.0 * st.inst.scale_value_rad;
    s.kappa = 0.002;
    s.reversals = 5;
    s.reading_noise = NoiseModel::white(t.sigma_tracking_arcsec * units::kArcsecond);
    for (double v : simulate_tracking(s, rng()))
      d.tracking.reversals_rad.push_back(wrap_positive_rad(rnd(v, 0.1 * units::kArcsecond)));
    if (t.sigma_tracking_arcsec > 0)
      d.tracking.sigma_reading_rad = t.sigma_tracking_arcsec * units::kArcsecond;
    return d;
  }
  d.mode = Mode::NonTracking;
  // Clamp within a few arc-minutes of north, on a whole arc-minute.
  const double offset = t.max_clamp_offset_arcmin * uni(rng) * kArcmin;
  d.clamp_reading_rad = wrap_positive_rad(round_to(north + offset, kArcmin));
  NonTrackingSimulation s;
  s.beta_div = beta_for_north(north, d.clamp_reading_rad, st.inst, ap);
  s.amplitude_div = t.amplitude_div;
  s.period_s = st.period_s;
  s.t0_s = 40.0 + 20.0 * uni(rng);
  s.levels_div = {-2.0, 0.0, 2.0};
  s.crossings_per_level = 3;
  s.start_time_s = 0.0;
  s.reversals = 2;
  s.record_reversal_times = false;
  s.time_noise = NoiseModel::white(t.sigma_time_s);
  s.reading_noise = NoiseModel::white(t.sigma_reading_div);
  s.known_period_s = rnd(st.period_s, 0.01);  // a stated period, as from the log
  s.known_period_sigma_s = 0.5;
  d.nontracking = simulate_nontracking(s, rng());
  for (auto& c : d.nontracking.crossings)
    for (auto& x : c.times_s) x = rnd(x, 0.001);
  for (auto& a : d.nontracking.reversals_div) a = rnd(a, 0.01);
  d.nontracking.sigma_time_s = t.sigma_time_s > 0 ? t.sigma_time_s : kDefaultSigmaTime_s;
  d.nontracking.sigma_reading_div = t.sigma_reading_div > 0 ? t.sigma_reading_div : kDefaultSigmaReading_div;
  return d;
}

// A station of the truth: its point, the instrument there and T_B rescaled to it by
// T_B² ∝ 1/(cos φ·(1+λ(φ))).
Station station_at(const CampaignTruth& t, const geodesy::TransverseMercatorGrid& grid, const PointInput& p,
                   const char* what) {
  Station s;
  s.point = locate(p, grid, what);
  s.inst = resolve_instrument(t.instrument, s.point.lat_rad).instrument;
  const double lat0 = t.instrument.constants_latitude_rad.value_or(s.point.lat_rad);
  const double lam0 = t.instrument.torsion_ratio ? t.instrument.torsion_ratio->value : s.inst.torsion_ratio.value;
  s.period_s = t.nontracking_period_s *
               std::sqrt(std::cos(lat0) * (1.0 + lam0) /
                         (std::cos(s.point.lat_rad) * (1.0 + s.inst.torsion_ratio.value)));
  return s;
}

// One line of the truth: its ends as given and located, η and ξ at its station.
struct TruthLine {
  const PointInput& from_in;
  const PointInput& to_in;
  const PointResult& from;
  const PointResult& to;
  double eta_rad;
  const std::optional<double>& xi_rad;
};

// Truth: grid azimuth of the chord → geodetic → astronomic → gyro azimuth; with ξ the full
// Laplace equation, z from the heights of the points. Returns the gyro azimuth and sets the
// grid azimuth.
double true_gyro_azimuth(const CampaignTruth& t, const geodesy::TransverseMercatorGrid& grid, const TruthLine& l,
                         double& grid_az) {
  const PointResult& from = l.from;
  const PointResult& to = l.to;
  const double T = std::atan2(to.grid.y_east_m - from.grid.y_east_m, to.grid.x_north_m - from.grid.x_north_m);
  const double delta =
      geodesy::arc_to_chord(grid, from.grid.x_north_m, from.grid.y_east_m, to.grid.x_north_m, to.grid.y_east_m);
  geodesy::AzimuthReduction r{from.lat_rad, Uncertain{l.eta_rad, 0.0}, from.grid.convergence_rad, delta};
  if (l.xi_rad) {
    r.xi_rad = Uncertain{*l.xi_rad, 0.0};
    if (l.from_in.height_m && l.to_in.height_m)
      r.zenith_distance_rad = geodesy::sight_zenith_distance_rad(
          {from.lat_rad, from.lon_rad, *l.from_in.height_m}, {to.lat_rad, to.lon_rad, *l.to_in.height_m},
          t.grid.ellipsoid);
  }
  const geodesy::AzimuthSteps s = geodesy::azimuth_steps(geodesy::AzimuthKind::Grid, {T, 0.0}, r);
  grid_az = s.grid_rad.value;
  return wrap_positive_rad(s.astronomic_rad.value - t.instrument_constant_rad);
}

// The known line as booked: its points (η, ξ when given), its grid azimuth (rounded), and the
// determinations before and after.
KnownLineInput simulated_known_line(const CampaignTruth& t, const Station& a, double gyro_az, double grid_az,
                                    std::mt19937_64& rng) {
  KnownLineInput kl;
  kl.from = t.known_station;
  kl.to = t.known_target;
  if (t.give_eta) kl.from.eta_rad = Uncertain{t.eta_known_rad, 0.5 * units::kArcsecond};
  if (t.give_eta && t.xi_known_rad) kl.from.xi_rad = Uncertain{*t.xi_known_rad, 0.5 * units::kArcsecond};
  kl.azimuth.kind = KnownAzimuth::Kind::Grid;
  kl.azimuth.value_rad = {Rounder{t.round_to_field_precision}(grid_az, 0.01 * units::kArcsecond),
                          t.known_azimuth_sigma_arcsec * units::kArcsecond};
  for (int i = 0; i < t.known_before; ++i)
    kl.before.push_back(simulate_determination(t, a, gyro_az, false, fmt::format("known line, before, #{}", i + 1), rng));
  for (int i = 0; i < t.known_after; ++i)
    kl.after.push_back(simulate_determination(t, a, gyro_az, false, fmt::format("known line, after, #{}", i + 1), rng));
  return kl;
}

// The unknown line as booked: its points and the non-tracking, then the tracking determinations.
LineInput simulated_line(const CampaignTruth& t, const Station& c, double gyro_az, std::mt19937_64& rng) {
  LineInput line;
  line.from = t.station;
  line.to = t.target;
  if (t.give_eta) line.from.eta_rad = Uncertain{t.eta_station_rad, 0.5 * units::kArcsecond};
  if (t.give_eta && t.xi_station_rad) line.from.xi_rad = Uncertain{*t.xi_station_rad, 0.5 * units::kArcsecond};
  int k = 0;
  for (int i = 0; i < t.line_nontracking; ++i)
    line.determinations.push_back(
        simulate_determination(t, c, gyro_az, false, fmt::format("line, non-tracking #{}", ++k), rng));
  for (int i = 0; i < t.line_tracking; ++i)
    line.determinations.push_back(
        simulate_determination(t, c, gyro_az, true, fmt::format("line, tracking #{}", ++k), rng));
  return line;
}

}  // namespace

SimulatedCampaign simulate_campaign(const CampaignTruth& t, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const geodesy::TransverseMercatorGrid grid(t.grid);
  SimulatedCampaign out;
  CampaignInput& in = out.input;
  in.name = t.name;
  in.instrument = t.instrument;
  in.grid = t.grid;
  const Station c = station_at(t, grid, t.station, "station");
  const Station a = station_at(t, grid, t.known_station, "known station");
  const PointResult d = locate(t.target, grid, "target");
  const PointResult b = locate(t.known_target, grid, "known target");
  const double ag_line = true_gyro_azimuth(
      t, grid, {t.station, t.target, c.point, d, t.eta_station_rad, t.xi_station_rad}, out.true_grid_azimuth_rad);
  const double ag_known =
      true_gyro_azimuth(t, grid, {t.known_station, t.known_target, a.point, b, t.eta_known_rad, t.xi_known_rad},
                        out.true_known_grid_azimuth_rad);
  in.known_line = simulated_known_line(t, a, ag_known, out.true_known_grid_azimuth_rad, rng);
  in.line = simulated_line(t, c, ag_line, rng);
  out.truth.push_back(fmt::format(
      "Truth: grid azimuth C-D {} ; known line A-B grid azimuth {} ; E = {:+.1f}\"",
      format_direction_dms(Angle::radians(out.true_grid_azimuth_rad), {3, true, false}),
      format_direction_dms(Angle::radians(out.true_known_grid_azimuth_rad), {3, true, false}),
      t.instrument_constant_rad / units::kArcsecond));
  return out;
}

CampaignTruth example_campaign_truth() {
  CampaignTruth t;
  t.name = "Shaft No. 3 - underground base line C-D";
  t.instrument.name = "simulated 15\"-class gyro-theodolite";
  t.instrument.scale_value_rad = 600.0 * units::kArcsecond;
  t.instrument.torsion_ratio = Uncertain{0.30, 0.003};
  t.instrument.constants_latitude_rad = 34.2 * units::kDegree;
  t.instrument.accuracy_class_arcsec = 15.0;
  t.nontracking_period_s = 440.0;
  t.grid = geodesy::gauss_kruger_3(38, geodesy::cgcs2000());
  // Near 37.85 N, 112.55 E: west of the zone's central meridian 114 E.
  t.known_station = {"A (surface)", {}, {}, 4191380.250, 372430.120, {}, 862.4};
  t.known_target = {"B (surface)", {}, {}, 4192655.870, 373118.440, {}, 871.9};
  t.station = {"C (shaft bottom)", {}, {}, 4190912.410, 372887.660, {}, 341.7};
  t.target = {"D (main drift)", {}, {}, 4190104.030, 373652.350, {}, 338.2};
  t.eta_station_rad = -4.2 * units::kArcsecond;
  t.eta_known_rad = -4.0 * units::kArcsecond;
  t.instrument_constant_rad = 25.4 * units::kArcsecond;
  return t;
}

}  // namespace meridian::gyro
