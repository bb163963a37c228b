#include "meridian/dov/deflection.hpp"

#include <cmath>
#include <string>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/geodesy/frames.hpp"
#include "meridian/filter/consistency.hpp"
#include "meridian/filter/innovation.hpp"
#include "meridian/filter/kalman_filter.hpp"
#include "meridian/filter/rts_smoother.hpp"
#include "meridian/filter/smoother_storage.hpp"

namespace meridian::dov {
namespace {

constexpr std::size_t kProgressStride = 1024;  // epochs between progress reports

std::string sample_field(std::size_t k, const char* member) {
  return fmt::format("samples[{}].{}", k, member);
}

[[noreturn]] void bad_sample(std::size_t k, const char* member, const std::string& message) {
  throw InputError(message, ErrorContext{{}, {}, sample_field(k, member)});
}

void require_option(bool ok, const char* name, const char* what, double value) {
  if (!ok)
    throw InputError(fmt::format("options.{} must be {}, is {}", name, what, value),
                     ErrorContext{{}, {}, std::string("options.") + name});
}

void check_finite(double v, std::size_t k, const char* member, const char* what) {
  if (!std::isfinite(v)) bad_sample(k, member, fmt::format("{} is not finite ({})", what, v));
}

/// The checks of step 1 of the file comment, except the time order.
void check_sample(const Sample& s, std::size_t k, const Options& o) {
  check_finite(s.time_s, k, "time_s", "time");
  check_finite(s.lat_rad, k, "lat_rad", "latitude");
  if (std::abs(s.lat_rad) > units::kPi / 2.0)
    bad_sample(k, "lat_rad", fmt::format("latitude {} rad is beyond ±π/2", s.lat_rad));
  check_finite(s.lon_rad, k, "lon_rad", "longitude");
  check_finite(s.height_m, k, "height_m", "height");
  check_finite(s.speed_m_s, k, "speed_m_s", "speed");
  if (s.speed_m_s < 0.0)
    bad_sample(k, "speed_m_s", fmt::format("speed must be ≥ 0, is {} m/s", s.speed_m_s));
  if (s.speed_m_s > kMaxSpeed_m_s)
    bad_sample(k, "speed_m_s",
               fmt::format("speed {} m/s is above {} m/s (a unit error?)", s.speed_m_s,
                           kMaxSpeed_m_s));
  if (!std::isfinite(s.model_eta_rad))
    bad_sample(k, "model_eta_rad",
               fmt::format("model value η_G is missing or not finite ({})", s.model_eta_rad));
  if (!std::isfinite(s.model_xi_rad))
    bad_sample(k, "model_xi_rad",
               fmt::format("model value ξ_G is missing or not finite ({})", s.model_xi_rad));
  // A model deflection beyond geodesy's bound (34′; the largest on Earth are about 1′) is a unit
  // or column error, not a value to filter.
  for (const auto& [v, member, name] :
       {std::tuple{s.model_eta_rad, "model_eta_rad", "η_G"},
        std::tuple{s.model_xi_rad, "model_xi_rad", "ξ_G"}})
    if (std::abs(v) > geodesy::kMaxDeflection_rad)
      bad_sample(k, member,
                 fmt::format("model value {} = {:.1f}″ is beyond ±{:.0f}″ (a unit error?)", name,
                             v / units::kArcsecond,
                             geodesy::kMaxDeflection_rad / units::kArcsecond));
  check_rotation(s.lgu_body_to_nav, sample_field(k, "lgu_body_to_nav"), o.orthogonality_tolerance);
  check_rotation(s.ins_body_to_nav, sample_field(k, "ins_body_to_nav"), o.orthogonality_tolerance);
}

DeflectionEstimate deflection_of(const filter::Estimate<State::size>& e, const Sample& s) {
  DeflectionEstimate d;
  d.eta_rad = s.model_eta_rad + e.x(State::delta_eta);
  d.xi_rad = s.model_xi_rad + e.x(State::delta_xi);
  d.sigma_eta_rad = e.sigma(State::delta_eta);
  d.sigma_xi_rad = e.sigma(State::delta_xi);
  d.eps_u_rad_s = e.x(State::eps_u);
  d.sigma_eps_u_rad_s = e.sigma(State::eps_u);
  return d;
}

/// The discretised model of the current step and the values it was made for.
struct ModelCache {
  bool valid = false;
  double dt_s = 0.0, lat_rad = 0.0, speed_m_s = 0.0;
  bool stationary = false;
  filter::DiscreteModel<State::size> step;
};

struct Accumulator {
  double sum = 0.0;
  std::size_t n = 0;
  void add(double v) {
    sum += v;
    ++n;
  }
  double mean() const { return n > 0 ? sum / static_cast<double>(n) : 0.0; }
  double rms() const { return std::sqrt(mean()); }
};

}  // namespace

void validate(const Options& o) {
  validate(o.model);
  validate(o.initial);
  observation_covariance(o.sigma_obs_east_rad, o.sigma_obs_north_rad);  // throws when ≤ 0
  require_option(std::isfinite(o.orthogonality_tolerance) && o.orthogonality_tolerance > 0.0,
                 "orthogonality_tolerance", "finite and > 0", o.orthogonality_tolerance);
  require_option(std::isfinite(o.max_attitude_difference_rad) &&
                     o.max_attitude_difference_rad > 0.0,
                 "max_attitude_difference_rad", "finite and > 0", o.max_attitude_difference_rad);
  require_option(std::isfinite(o.max_step_s) && o.max_step_s > 0.0, "max_step_s",
                 "finite and > 0", o.max_step_s);
  require_option(std::isfinite(o.step_tolerance) && o.step_tolerance >= 0.0, "step_tolerance",
                 "finite and ≥ 0", o.step_tolerance);
  require_option(std::isfinite(o.rediscretise_latitude_rad) && o.rediscretise_latitude_rad >= 0.0,
                 "rediscretise_latitude_rad", "finite and ≥ 0", o.rediscretise_latitude_rad);
  require_option(std::isfinite(o.rediscretise_speed_m_s) && o.rediscretise_speed_m_s >= 0.0,
                 "rediscretise_speed_m_s", "finite and ≥ 0", o.rediscretise_speed_m_s);
  require_option(o.gate_alpha == 0.0 || (o.gate_alpha > 0.0 && o.gate_alpha < 1.0), "gate_alpha",
                 "0 (no gate) or in (0, 1)", o.gate_alpha);
  require_option(std::isfinite(o.statistics_start_s) && o.statistics_start_s >= 0.0,
                 "statistics_start_s", "finite and ≥ 0", o.statistics_start_s);
}

Result process(const Input& input, Progress* progress) {
  const Options& o = input.options;
  validate(o);
  const std::vector<Sample>& samples = input.samples;
  const std::size_t n = samples.size();
  if (n < 2)
    throw InputError(fmt::format("a line needs at least 2 samples, has {}", n),
                     ErrorContext{{}, {}, "samples"});
  if (!input.truth.empty() && input.truth.size() != n)
    throw InputError(fmt::format("truth has {} entries for {} samples (give none or one per "
                                 "sample)",
                                 input.truth.size(), n),
                     ErrorContext{{}, {}, "truth"});
  const bool have_truth = !input.truth.empty();
  for (std::size_t k = 0; k < input.truth.size(); ++k) {
    const Truth& t = input.truth[k];
    const auto field = [&](const char* m) { return fmt::format("truth[{}].{}", k, m); };
    if (!std::isfinite(t.eta_rad) || !std::isfinite(t.xi_rad))
      throw InputError("true deflection is not finite", ErrorContext{{}, {}, field("eta_rad")});
    if (t.state && !t.state->allFinite())
      throw InputError("true state is not finite", ErrorContext{{}, {}, field("state")});
    if (t.state.has_value() != input.truth.front().state.has_value())
      throw InputError("a true state is given for some samples only",
                       ErrorContext{{}, {}, field("state")});
  }
  const bool have_states = have_truth && input.truth.front().state.has_value();

  Result result;
  result.epochs.resize(n);

  // Reference speed of the initial x-variance: the first moving sample.
  double reference_speed = 0.0;
  for (const Sample& s : samples)
    if (std::isfinite(s.speed_m_s) && s.speed_m_s >= 0.0 && !is_stationary(s.speed_m_s, o.model)) {
      reference_speed = s.speed_m_s;
      break;
    }
  const filter::Estimate<State::size> initial =
      initial_estimate(o.initial, o.model, reference_speed);
  if (!o.initial.x_rad_s)
    result.notes.push_back(
        reference_speed > 0.0
            ? fmt::format("initial σ of x_E, x_N: σ_model/ω₀ at the first moving speed {} m/s",
                          reference_speed)
            : std::string("the whole line is stationary: x_E, x_N are decoupled"));
  if (!o.initial.delta_rad)
    result.notes.push_back("initial σ of δη, δξ: σ_model (the model's stationary value)");

  const ObservationMatrix H = observation_matrix();
  const ObservationCovariance R = observation_covariance(o.sigma_obs_east_rad, o.sigma_obs_north_rad);
  const filter::InnovationGate gate =
      o.gate_alpha > 0.0 ? filter::InnovationGate(o.gate_alpha) : filter::InnovationGate();
  filter::KalmanFilter<State::size> kf(initial, gate);
  filter::SmootherStorage<State::size> storage(State::size, o.storage);
  ModelCache cache;
  std::size_t stationary_steps = 0;

  for (std::size_t k = 0; k < n; ++k) {
    const Sample& s = samples[k];
    check_sample(s, k, o);
    if (k > 0) {
      const Sample& p = samples[k - 1];
      const double dt = s.time_s - p.time_s;
      if (!(dt > 0.0))
        bad_sample(k, "time_s",
                   fmt::format("time {} s is not after the previous sample's {} s", s.time_s,
                               p.time_s));
      if (dt > o.max_step_s)
        bad_sample(k, "time_s",
                   fmt::format("gap of {} s after the previous sample exceeds options.max_step_s "
                               "= {} s",
                               dt, o.max_step_s));
      const double lat = 0.5 * (s.lat_rad + p.lat_rad);
      const double speed = 0.5 * (s.speed_m_s + p.speed_m_s);
      const bool stationary = is_stationary(speed, o.model);
      if (stationary) ++stationary_steps;
      if (!cache.valid || std::abs(dt - cache.dt_s) > o.step_tolerance * cache.dt_s ||
          std::abs(lat - cache.lat_rad) > o.rediscretise_latitude_rad ||
          std::abs(speed - cache.speed_m_s) > o.rediscretise_speed_m_s ||
          stationary != cache.stationary) {
        cache.step = discrete_model(lat, speed, dt, o.model, o.discretisation);
        cache.valid = true;
        cache.dt_s = dt;
        cache.lat_rad = lat;
        cache.speed_m_s = speed;
        cache.stationary = stationary;
        ++result.summary.discretisations;
      }
      kf.predict(cache.step);
    }
    const Eigen::Matrix3d c = attitude_difference_matrix(s.lgu_body_to_nav, s.ins_body_to_nav);
    // Both matrices make the difference: the error names neither one alone.
    const AttitudeDifference d = extract(c, o.extraction, sample_field(k, "attitude_difference"));
    const double size = d.vector().norm();
    if (!(size <= o.max_attitude_difference_rad))
      bad_sample(k, "attitude_difference",
                 fmt::format("the two attitude matrices differ by {:.4g}° (limit {:.4g}°, "
                             "options.max_attitude_difference_rad): do they describe the same "
                             "body and frame order?",
                             size / units::kDegree, o.max_attitude_difference_rad / units::kDegree));
    filter::Vector<Obs::size> y;
    y(Obs::east) = d.east_rad - s.model_xi_rad;
    y(Obs::north) = d.north_rad + s.model_eta_rad;
    const filter::Innovation<Obs::size> in = kf.update(y, H, R);
    storage.append(kf.predicted(), kf.transition(), kf.estimate());

    EpochResult& e = result.epochs[k];
    e.time_s = s.time_s;
    e.model_eta_rad = s.model_eta_rad;
    e.model_xi_rad = s.model_xi_rad;
    e.observed = d;
    e.filtered = deflection_of(kf.estimate(), s);
    e.innovation_east_rad = in.nu(Obs::east);
    e.innovation_north_rad = in.nu(Obs::north);
    e.sigma_innovation_east_rad = std::sqrt(in.S(Obs::east, Obs::east));
    e.sigma_innovation_north_rad = std::sqrt(in.S(Obs::north, Obs::north));
    e.nis = in.nis;
    e.accepted = in.accepted;
    if (!in.accepted) ++result.summary.rejected;
    if (have_states)
      e.nees_filtered =
          filter::nees<State::size>(*input.truth[k].state, kf.estimate(),
                                    static_cast<Eigen::Index>(k));
    if (k % kProgressStride == 0) report_progress(progress, k, 2 * n, "filtering");
  }

  std::size_t done = 0;
  filter::rts_smooth(storage, [&](Eigen::Index k, const filter::Estimate<State::size>& sm) {
    const auto i = static_cast<std::size_t>(k);
    EpochResult& e = result.epochs[i];
    e.smoothed = deflection_of(sm, samples[i]);
    if (have_states) e.nees_smoothed = filter::nees<State::size>(*input.truth[i].state, sm, k);
    if (++done % kProgressStride == 0) report_progress(progress, n + done, 2 * n, "smoothing");
  });
  report_progress(progress, 2 * n, 2 * n, "smoothing");

  // Summary.
  Summary& sum = result.summary;
  sum.epochs = n;
  const double t0 = samples.front().time_s;
  Accumulator nis, sf_eta, sf_xi, ss_eta, ss_xi, m_eta, m_xi, f_eta, f_xi, s_eta, s_xi, nees_f,
      nees_s;
  for (std::size_t k = 0; k < n; ++k) {
    const EpochResult& e = result.epochs[k];
    if (e.time_s - t0 < o.statistics_start_s) continue;
    ++sum.statistics_epochs;
    if (e.accepted) nis.add(e.nis);
    sf_eta.add(e.filtered.sigma_eta_rad * e.filtered.sigma_eta_rad);
    sf_xi.add(e.filtered.sigma_xi_rad * e.filtered.sigma_xi_rad);
    ss_eta.add(e.smoothed.sigma_eta_rad * e.smoothed.sigma_eta_rad);
    ss_xi.add(e.smoothed.sigma_xi_rad * e.smoothed.sigma_xi_rad);
    if (have_truth) {
      const Truth& t = input.truth[k];
      const auto sq = [](double v) { return v * v; };
      m_eta.add(sq(e.model_eta_rad - t.eta_rad));
      m_xi.add(sq(e.model_xi_rad - t.xi_rad));
      f_eta.add(sq(e.filtered.eta_rad - t.eta_rad));
      f_xi.add(sq(e.filtered.xi_rad - t.xi_rad));
      s_eta.add(sq(e.smoothed.eta_rad - t.eta_rad));
      s_xi.add(sq(e.smoothed.xi_rad - t.xi_rad));
    }
    if (have_states) {
      nees_f.add(*e.nees_filtered);
      nees_s.add(*e.nees_smoothed);
    }
  }
  if (sum.statistics_epochs == 0)
    throw InputError(fmt::format("options.statistics_start_s = {} s leaves no epoch in the "
                                 "statistics (the line lasts {} s)",
                                 o.statistics_start_s, samples.back().time_s - t0),
                     ErrorContext{{}, {}, "options.statistics_start_s"});
  sum.mean_nis = nis.mean();
  if (nis.n > 0) {
    sum.nis_interval =
        filter::average_interval(Obs::size, static_cast<std::int64_t>(nis.n), 0.95);
    if (!sum.nis_interval.contains(sum.mean_nis))
      result.warnings.push_back(fmt::format(
          "mean NIS {:.3f} is outside its 95 % interval [{:.3f}, {:.3f}]: the noise model "
          "(σ_model, r, P₀) does not fit the data",
          sum.mean_nis, sum.nis_interval.lower, sum.nis_interval.upper));
  }
  // The mean NIS is over the accepted updates only, so a gate that rejects far more than its
  // α·N can hide a misfit there: say so (α·N plus 3 binomial σ plus 2).
  if (o.gate_alpha > 0.0) {
    const double expected = o.gate_alpha * static_cast<double>(n);
    const double limit = expected + 3.0 * std::sqrt(expected * (1.0 - o.gate_alpha)) + 2.0;
    if (static_cast<double>(sum.rejected) > limit)
      result.warnings.push_back(fmt::format(
          "the innovation gate rejected {} of {} updates, about {:.0f} expected at alpha = {:g}: "
          "the noise model (sigma_model, r, P0) does not fit the data or the line has blunders; "
          "the mean NIS above is over the accepted updates only",
          sum.rejected, n, expected, o.gate_alpha));
  }
  sum.rms_sigma_filtered = {sf_eta.rms(), sf_xi.rms()};
  sum.rms_sigma_smoothed = {ss_eta.rms(), ss_xi.rms()};
  if (have_truth) {
    sum.rms_model = EtaXi{m_eta.rms(), m_xi.rms()};
    sum.rms_filtered = EtaXi{f_eta.rms(), f_xi.rms()};
    sum.rms_smoothed = EtaXi{s_eta.rms(), s_xi.rms()};
  }
  if (have_states) {
    sum.mean_nees_filtered = nees_f.mean();
    sum.mean_nees_smoothed = nees_s.mean();
  }
  sum.eps_u_rad_s = result.epochs.front().smoothed.eps_u_rad_s;
  sum.sigma_eps_u_rad_s = result.epochs.front().smoothed.sigma_eps_u_rad_s;
  if (stationary_steps > 0)
    result.notes.push_back(fmt::format(
        "{} of {} steps stationary (V < {} m/s): δη, δξ held constant, x_E, x_N frozen",
        stationary_steps, n - 1, o.model.stationary_speed_m_s));
  if (progress) progress->finish();
  return result;
}

}  // namespace meridian::dov
