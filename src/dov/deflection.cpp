#include "meridian/dov/deflection.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/dov/streaming.hpp"
#include "meridian/filter/detail/record_store.hpp"
#include "meridian/geodesy/frames.hpp"
#include "meridian/filter/consistency.hpp"
#include "meridian/filter/innovation.hpp"
#include "meridian/filter/kalman_filter.hpp"
#include "meridian/filter/rts_smoother.hpp"
#include "meridian/filter/smoother_storage.hpp"

namespace meridian::dov {
namespace {

constexpr std::size_t kProgressStride = 1024;  // epochs between progress reports
constexpr std::size_t kChunk = 4096;           // samples asked of the source at a time

// Field names of the per-sample checks (built once; the index is added on failure).
const std::string kLguField = "lgu_body_to_nav";
const std::string kInsField = "ins_body_to_nav";
const std::string kDifferenceField = "attitude_difference";

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
  // The sample's index goes into the field only when a check fails: formatting
  // "samples[k].member" for every sample cost about 5 % of the workflow (perf).
  try {
    check_rotation(s.lgu_body_to_nav, kLguField, o.orthogonality_tolerance);
    check_rotation(s.ins_body_to_nav, kInsField, o.orthogonality_tolerance);
  } catch (Error& e) {
    e.add_context({}, {}, fmt::format("samples[{}]", k));
    throw;
  }
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

/// The stop/start class of the samples (deflection.hpp, Stops): causal, with hysteresis.
class StopDetector {
 public:
  StopDetector(double threshold_m_s, double min_duration_s)
      : threshold_(threshold_m_s), min_duration_(min_duration_s) {}
  /// The class after the sample at time_s with speed_m_s: true when stationary.
  bool add(double time_s, double speed_m_s) {
    const bool below = speed_m_s < threshold_ || speed_m_s == 0.0;
    if (!started_) {
      started_ = true;
      stationary_ = below;
    } else if (below == stationary_) {
      pending_ = false;
    } else {
      if (!pending_) {
        pending_ = true;
        pending_since_ = time_s;
      }
      if (time_s - pending_since_ >= min_duration_) {
        stationary_ = below;
        pending_ = false;
      }
    }
    return stationary_;
  }

 private:
  double threshold_, min_duration_;
  bool started_ = false, stationary_ = false, pending_ = false;
  double pending_since_ = 0.0;
};

/// P₀'s reference speed (deflection.hpp): the median speed ≥ V_s over the first `window` s of
/// motion, motion beginning with the first run at ≥ V_s of at least `min_duration` s.
class ReferenceSpeed {
 public:
  ReferenceSpeed(double threshold_m_s, double min_duration_s, double window_s)
      : threshold_(threshold_m_s), min_duration_(min_duration_s), window_(window_s) {}
  /// The next sample; true once the speed is decided (later samples are then ignored).
  bool add(double time_s, double speed_m_s) {
    if (decided_) return true;
    const bool above = !(speed_m_s < threshold_) && speed_m_s > 0.0;
    if (!confirmed_) {
      if (!above) {
        run_.clear();
        return false;
      }
      if (run_.empty()) run_start_ = time_s;
      run_.push_back(speed_m_s);
      if (time_s - run_start_ >= min_duration_) confirmed_ = true;
      return decided_ = confirmed_ && time_s - run_start_ >= window_;
    }
    if (time_s - run_start_ > window_) return decided_ = true;
    if (above) run_.push_back(speed_m_s);
    return decided_ = time_s - run_start_ >= window_;
  }
  /// The speed (m/s) once decided or at the end of the line (a run that reaches it counts);
  /// 0 when the line never moves.
  double value() {
    if (run_.empty()) return 0.0;
    const auto mid = run_.begin() + static_cast<std::ptrdiff_t>(run_.size() / 2);
    std::nth_element(run_.begin(), mid, run_.end());
    if (run_.size() % 2 == 1) return *mid;
    return 0.5 * (*mid + *std::max_element(run_.begin(), mid));
  }

 private:
  double threshold_, min_duration_, window_;
  bool confirmed_ = false, decided_ = false;
  double run_start_ = 0.0;
  std::vector<double> run_;
};

/// The discretised model of the current step and the values it was made for.
struct ModelCache {
  bool valid = false;
  double dt_s = 0.0, lat_rad = 0.0, speed_m_s = 0.0;
  bool stationary = false;
  Eigen::Vector3d transport_rate_rad_s = Eigen::Vector3d::Zero();
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

// Epoch results in the record stores of process_stream: kRecordDoubles doubles, NaN for an
// absent optional (outputs are never NaN, so NaN cannot be a value).
constexpr std::size_t kRecordDoubles = 38;

void pack_estimate(const DeflectionEstimate& d, double* p) {
  p[0] = d.eta_rad;
  p[1] = d.xi_rad;
  p[2] = d.sigma_eta_rad;
  p[3] = d.sigma_xi_rad;
  p[4] = d.eps_u_rad_s;
  p[5] = d.sigma_eps_u_rad_s;
}

DeflectionEstimate unpack_estimate(const double* p) {
  return {p[0], p[1], p[2], p[3], p[4], p[5]};
}

/// Layout: 0 time, 1 lat, 2 lon, 3–4 model, 5–7 ΔΦ, 8–13 filtered, 14–19 smoothed,
/// 20–23 innovations and their σ, 24 NIS, 25 accepted, 26–27 NEES, 28–29 truth, 30–37 state.
void pack(const EpochResult& e, const StateVector* state, double* p) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  p[0] = e.time_s;
  p[1] = e.lat_rad;
  p[2] = e.lon_rad;
  p[3] = e.model_eta_rad;
  p[4] = e.model_xi_rad;
  p[5] = e.observed.east_rad;
  p[6] = e.observed.north_rad;
  p[7] = e.observed.up_rad;
  pack_estimate(e.filtered, p + 8);
  pack_estimate(e.smoothed, p + 14);
  p[20] = e.innovation_east_rad;
  p[21] = e.innovation_north_rad;
  p[22] = e.sigma_innovation_east_rad;
  p[23] = e.sigma_innovation_north_rad;
  p[24] = e.nis;
  p[25] = e.accepted ? 1.0 : 0.0;
  p[26] = e.nees_filtered.value_or(nan);
  p[27] = e.nees_smoothed.value_or(nan);
  p[28] = e.truth ? e.truth->eta_rad : nan;
  p[29] = e.truth ? e.truth->xi_rad : nan;
  for (int i = 0; i < State::size; ++i) p[30 + i] = state ? (*state)(i) : nan;
}

/// What process_stream keeps of each forward epoch for the backward pass. With a sink, the
/// whole epoch (pack, kRecordDoubles); without one only what the smoothed statistics read: η_G,
/// ξ_G and the true η, ξ when the line has truth, and the true state for the NEES — 0 to 12
/// doubles instead of 38, so a line of millions of epochs keeps them in memory instead of
/// spilling 304 bytes an epoch to disk and reading them back (issue 10).
struct EpochLayout {
  bool full = true;     // the whole EpochResult (a sink receives every field)
  bool truth = false;   // slim: η_G, ξ_G, true η, ξ
  bool states = false;  // slim: the true state
  std::size_t doubles() const {
    return full ? kRecordDoubles : (truth ? 4 : 0) + (states ? State::size : 0);
  }
};

void pack_slim(const EpochLayout& l, const Sample& s, const Truth* truth, double* p) {
  if (l.truth) {
    p[0] = s.model_eta_rad;
    p[1] = s.model_xi_rad;
    p[2] = truth->eta_rad;
    p[3] = truth->xi_rad;
    p += 4;
  }
  if (l.states)
    for (int i = 0; i < State::size; ++i) p[i] = (*truth->state)(i);
}

void unpack_slim(const EpochLayout& l, const double* p, EpochResult& e, StateVector& state) {
  if (l.truth) {
    e.model_eta_rad = p[0];
    e.model_xi_rad = p[1];
    e.truth = EtaXi{p[2], p[3]};
    p += 4;
  }
  if (l.states)
    for (int i = 0; i < State::size; ++i) state(i) = p[i];
}

void unpack(const double* p, EpochResult& e, StateVector* state) {
  e.time_s = p[0];
  e.lat_rad = p[1];
  e.lon_rad = p[2];
  e.model_eta_rad = p[3];
  e.model_xi_rad = p[4];
  e.observed = {p[5], p[6], p[7]};
  e.filtered = unpack_estimate(p + 8);
  e.smoothed = unpack_estimate(p + 14);
  e.innovation_east_rad = p[20];
  e.innovation_north_rad = p[21];
  e.sigma_innovation_east_rad = p[22];
  e.sigma_innovation_north_rad = p[23];
  e.nis = p[24];
  e.accepted = p[25] != 0.0;
  e.nees_filtered = std::isnan(p[26]) ? std::nullopt : std::optional<double>(p[26]);
  e.nees_smoothed = std::isnan(p[27]) ? std::nullopt : std::optional<double>(p[27]);
  e.truth = std::isnan(p[28]) ? std::nullopt : std::optional<EtaXi>(EtaXi{p[28], p[29]});
  if (state)
    for (int i = 0; i < State::size; ++i) (*state)(i) = p[30 + i];
}

/// P⁻ = Φ·P·Φᵀ + Q_d unrolled for the model's structure (model.hpp): the same numbers as the
/// generic sparse kernel, in about half the instructions (issue 10).
constexpr filter::TransitionKernel<State::size> kTransitionKernel =
    filter::structured_transition_kernel<State::size, transition_structure()>();

/// The model options with the workflow's stationary threshold.
ModelOptions model_with_threshold(const Options& o) {
  ModelOptions m = o.model;
  m.stationary_speed_m_s = stationary_threshold_m_s(o);
  return m;
}

/// The forward pass of process_stream: one sample at a time, steps 1–5 of deflection.hpp.
class Forward {
 public:
  /// `epochs` receives each epoch in `layout` (nullptr when it has no doubles); notes go to
  /// out.notes, counts to out.summary.
  Forward(const Options& o, double reference_speed, Result& out, EpochLayout layout,
          filter::detail::RecordStore* epochs)
      : o_(o),
        H_(observation_matrix()),
        R_(observation_covariance(o.sigma_obs_east_rad, o.sigma_obs_north_rad)),
        kf_(initial_estimate(o.initial, model_with_threshold(o), reference_speed),
            o.gate_alpha > 0.0 ? filter::InnovationGate(o.gate_alpha) : filter::InnovationGate()),
        storage_(State::size, o.storage),
        layout_(layout),
        epochs_(epochs),
        out_(out),
        model_(model_with_threshold(o)),
        stops_(model_.stationary_speed_m_s, o.stationary_min_duration_s),
        whiteness_(Obs::size, o.whiteness_max_lag) {
    kf_.set_transition_kernel(&kTransitionKernel);
    if (!o.initial.x_rad_s)
      out.notes.push_back(
          reference_speed > 0.0
              ? fmt::format("initial σ of x_E, x_N: σ_model/ω₀ at the reference speed {:.4g} m/s "
                            "(the median speed of the first {} s of motion)",
                            reference_speed, o.reference_speed_window_s)
              : std::string("the whole line is stationary: x_E, x_N are decoupled"));
    if (!o.initial.delta_rad)
      out.notes.push_back("initial σ of δη, δξ: σ_model (the model's stationary value)");
    if (o.transport_rate)
      out.notes.push_back(fmt::format(
          "transport rate: ω_en from the track's mean latitude and longitude rates over "
          "baselines of at least {} s, zero until the first one closes",
          o.transport_rate_baseline_s));
  }

  void add(const Sample& s, const Truth* truth) {
    const std::size_t k = n_;
    if (truth) check_truth(*truth, k);
    check_sample(s, k, o_);
    stationary_ = stops_.add(s.time_s, s.speed_m_s);
    if (k > 0)
      predict(s, k);
    else
      start(s);
    const AttitudeDifference d = observe(s, k);
    const filter::Innovation<Obs::size> in = update(s, d);
    const EpochResult e = epoch_result(s, truth, d, in, k);
    if (layout_.full)
      pack(e, have_states_ ? &*truth->state : nullptr, epochs_->append(k));
    else if (epochs_)
      pack_slim(layout_, s, truth, epochs_->append(k));
    accumulate(s, truth, e);
    prev_time_ = s.time_s;
    prev_lat_ = s.lat_rad;
    prev_speed_ = s.speed_m_s;
    ++n_;
  }

  std::size_t size() const { return n_; }
  double t0() const { return t0_; }
  double last_time() const { return prev_time_; }
  bool have_states() const { return have_states_; }
  std::size_t stationary_steps() const { return stationary_steps_; }
  filter::SmootherStorage<State::size>& storage() { return storage_; }
  const filter::LjungBox& whiteness() const { return whiteness_; }
  double stationary_threshold() const { return model_.stationary_speed_m_s; }

  Accumulator nis_, sf_eta_, sf_xi_, m_eta_, m_xi_, f_eta_, f_xi_, nees_f_;

 private:
  // The truth of sample k: finite, and a true state for every sample or for none.
  void check_truth(const Truth& truth, std::size_t k) {
    const auto field = [&](const char* m) { return fmt::format("truth[{}].{}", k, m); };
    if (!std::isfinite(truth.eta_rad) || !std::isfinite(truth.xi_rad))
      throw InputError("true deflection is not finite", ErrorContext{{}, {}, field("eta_rad")});
    if (truth.state && !truth.state->allFinite())
      throw InputError("true state is not finite", ErrorContext{{}, {}, field("state")});
    if (k == 0) have_states_ = truth.state.has_value();
    if (truth.state.has_value() != have_states_)
      throw InputError("a true state is given for some samples only",
                       ErrorContext{{}, {}, field("state")});
  }

  // Epoch 0: the start of the line and of the first transport-rate baseline.
  void start(const Sample& s) {
    t0_ = s.time_s;
    baseline_time_ = s.time_s;
    baseline_lat_ = s.lat_rad;
    baseline_lon_ = s.lon_rad;
  }

  // Step 3: predict over t_k − t_{k−1} with the model of the step, re-discretised only when
  // the step's length, mean latitude or speed, the stationarity or ω_en changed.
  void predict(const Sample& s, std::size_t k) {
    const double dt = s.time_s - prev_time_;
    if (!(dt > 0.0))
      bad_sample(k, "time_s",
                 fmt::format("time {} s is not after the previous sample's {} s", s.time_s,
                             prev_time_));
    if (dt > o_.max_step_s)
      bad_sample(k, "time_s",
                 fmt::format("gap of {} s after the previous sample exceeds options.max_step_s "
                             "= {} s",
                             dt, o_.max_step_s));
    const double lat = 0.5 * (s.lat_rad + prev_lat_);
    // The step's class is the detector's after sample k (deflection.hpp, Stops): stationary at
    // V = 0, moving at no less than the threshold.
    const bool stationary = stationary_;
    const double speed =
        stationary ? 0.0 : std::max(0.5 * (s.speed_m_s + prev_speed_), model_.stationary_speed_m_s);
    if (stationary) ++stationary_steps_;
    if (o_.transport_rate && s.time_s - baseline_time_ >= o_.transport_rate_baseline_s)
      close_baseline(s);
    if (!cache_.valid || std::abs(dt - cache_.dt_s) > o_.step_tolerance * cache_.dt_s ||
        std::abs(lat - cache_.lat_rad) > o_.rediscretise_latitude_rad ||
        std::abs(speed - cache_.speed_m_s) > o_.rediscretise_speed_m_s ||
        stationary != cache_.stationary || transport_rate_ != cache_.transport_rate_rad_s) {
      cache_.step = discrete_model(lat, speed, dt, model_, o_.discretisation, transport_rate_);
      cache_.valid = true;
      cache_.dt_s = dt;
      cache_.lat_rad = lat;
      cache_.speed_m_s = speed;
      cache_.stationary = stationary;
      cache_.transport_rate_rad_s = transport_rate_;
      ++out_.summary.discretisations;
    }
    kf_.predict(cache_.step);
  }

  // Options::transport_rate: the mean rates over the baseline that closes at `s`.
  void close_baseline(const Sample& s) {
    const double span = s.time_s - baseline_time_;
    const double dlon = std::remainder(s.lon_rad - baseline_lon_, 2.0 * units::kPi);
    transport_rate_ = transport_rate(0.5 * (s.lat_rad + baseline_lat_),
                                     (s.lat_rad - baseline_lat_) / span, dlon / span);
    baseline_time_ = s.time_s;
    baseline_lat_ = s.lat_rad;
    baseline_lon_ = s.lon_rad;
    ++out_.summary.transport_rate_updates;
  }

  // Step 2: ΔΦ of sample k, within max_attitude_difference_rad. Both matrices make the
  // difference: an error names neither one alone.
  AttitudeDifference observe(const Sample& s, std::size_t k) const {
    const Eigen::Matrix3d c = attitude_difference_matrix(s.lgu_body_to_nav, s.ins_body_to_nav);
    AttitudeDifference d;
    try {
      d = extract(c, o_.extraction, kDifferenceField);
    } catch (Error& e) {
      e.add_context({}, {}, fmt::format("samples[{}]", k));
      throw;
    }
    const double size = d.vector().norm();
    if (!(size <= o_.max_attitude_difference_rad))
      bad_sample(k, "attitude_difference",
                 fmt::format("the two attitude matrices differ by {:.4g}° (limit {:.4g}°, "
                             "options.max_attitude_difference_rad): do they describe the same "
                             "body and frame order?",
                             size / units::kDegree, o_.max_attitude_difference_rad / units::kDegree));
    return d;
  }

  // Step 4: the update with y = [ΔΦ_E − ξ_G, ΔΦ_N + η_G]ᵀ; its record goes to the smoother.
  filter::Innovation<Obs::size> update(const Sample& s, const AttitudeDifference& d) {
    filter::Vector<Obs::size> y;
    y(Obs::east) = d.east_rad - s.model_xi_rad;
    y(Obs::north) = d.north_rad + s.model_eta_rad;
    const filter::Innovation<Obs::size> in = kf_.update(y, H_, R_);
    storage_.append(kf_);  // compact records: P⁻ recomputed when read back
    return in;
  }

  // Step 5: the epoch's outputs of the forward pass (the smoothed ones come backward).
  EpochResult epoch_result(const Sample& s, const Truth* truth, const AttitudeDifference& d,
                           const filter::Innovation<Obs::size>& in, std::size_t k) {
    EpochResult e;
    e.time_s = s.time_s;
    e.lat_rad = s.lat_rad;
    e.lon_rad = s.lon_rad;
    e.model_eta_rad = s.model_eta_rad;
    e.model_xi_rad = s.model_xi_rad;
    if (truth) e.truth = EtaXi{truth->eta_rad, truth->xi_rad};
    e.observed = d;
    e.filtered = deflection_of(kf_.estimate(), s);
    e.innovation_east_rad = in.nu(Obs::east);
    e.innovation_north_rad = in.nu(Obs::north);
    e.sigma_innovation_east_rad = std::sqrt(in.S(Obs::east, Obs::east));
    e.sigma_innovation_north_rad = std::sqrt(in.S(Obs::north, Obs::north));
    e.nis = in.nis;
    e.accepted = in.accepted;
    // S^{-1/2}·ν by the Cholesky factor of the 2×2 S: two independent N(0, 1) for a correct
    // model (the whiteness test's series)
    const double l00 = std::sqrt(in.S(0, 0));
    const double l10 = in.S(1, 0) / l00;
    const double l11 = std::sqrt(std::max(in.S(1, 1) - l10 * l10, 0.0));
    whitened_[0] = in.nu(0) / l00;
    whitened_[1] = l11 > 0.0 ? (in.nu(1) - l10 * whitened_[0]) / l11 : 0.0;
    if (!in.accepted) ++out_.summary.rejected;
    if (have_states_)
      e.nees_filtered = filter::nees<State::size>(*truth->state, kf_.estimate(),
                                                  static_cast<Eigen::Index>(k));
    return e;
  }

  // The forward statistics of the epochs with t − t₀ ≥ statistics_start_s.
  void accumulate(const Sample& s, const Truth* truth, const EpochResult& e) {
    if (!(s.time_s - t0_ >= o_.statistics_start_s)) return;
    ++out_.summary.statistics_epochs;
    if (e.accepted) {
      nis_.add(e.nis);
      whiteness_.add(whitened_.data());
    }
    sf_eta_.add(e.filtered.sigma_eta_rad * e.filtered.sigma_eta_rad);
    sf_xi_.add(e.filtered.sigma_xi_rad * e.filtered.sigma_xi_rad);
    if (truth) {
      const auto sq = [](double v) { return v * v; };
      m_eta_.add(sq(e.model_eta_rad - truth->eta_rad));
      m_xi_.add(sq(e.model_xi_rad - truth->xi_rad));
      f_eta_.add(sq(e.filtered.eta_rad - truth->eta_rad));
      f_xi_.add(sq(e.filtered.xi_rad - truth->xi_rad));
    }
    if (have_states_) nees_f_.add(*e.nees_filtered);
  }

  const Options& o_;
  ObservationMatrix H_;
  ObservationCovariance R_;
  filter::KalmanFilter<State::size> kf_;
  filter::SmootherStorage<State::size> storage_;
  EpochLayout layout_;
  filter::detail::RecordStore* epochs_;
  Result& out_;
  ModelOptions model_;  // o_.model with the threshold of stationary_threshold_m_s
  StopDetector stops_;
  bool stationary_ = false;  // the class after the current sample
  filter::LjungBox whiteness_;
  std::array<double, Obs::size> whitened_{};
  ModelCache cache_;
  std::size_t n_ = 0;
  std::size_t stationary_steps_ = 0;
  bool have_states_ = false;
  double t0_ = 0.0, prev_time_ = 0.0, prev_lat_ = 0.0, prev_speed_ = 0.0;
  // Options::transport_rate: the open baseline's first sample and the current ω_en (ENU).
  double baseline_time_ = 0.0, baseline_lat_ = 0.0, baseline_lon_ = 0.0;
  Eigen::Vector3d transport_rate_ = Eigen::Vector3d::Zero();
};

/// The epochs a Result keeps (EpochOutputs::keep_epochs): every `every`-th epoch, the spacing
/// doubled whenever more than `at_most` are held, so memory stays bounded.
class KeptEpochs {
 public:
  KeptEpochs(std::size_t at_most, std::optional<std::size_t> line_size) : at_most_(at_most) {
    if (at_most_ > 0 && line_size) kept_.reserve(std::min(at_most_, *line_size));
  }
  void add(const EpochResult& e) {
    if (at_most_ == 0 || seen_++ % every_ != 0) return;
    kept_.push_back(e);
    if (kept_.size() > at_most_) {
      std::size_t j = 0;
      for (std::size_t i = 0; i < kept_.size(); i += 2) kept_[j++] = kept_[i];
      kept_.resize(j);
      every_ *= 2;
    }
  }
  std::vector<EpochResult> take() { return std::move(kept_); }
  std::size_t every() const { return every_; }

 private:
  std::size_t at_most_;
  std::vector<EpochResult> kept_;
  std::size_t every_ = 1;
  std::size_t seen_ = 0;
};

/// process_stream step by step (streaming.hpp): the samples up to the first moving one, the
/// forward pass, the backward pass (the smoother), the epochs handed out in time order, the
/// summary; the Result is built here, once.
class LineRun {
 public:
  LineRun(SampleSource& source, const Options& o, const EpochOutputs& outputs, Progress* progress)
      : source_(source),
        o_(o),
        outputs_(outputs),
        progress_(progress),
        have_truth_(source.has_truth()),
        total_(source.size_hint().value_or(0)),
        hand_out_(static_cast<bool>(outputs.sink) || outputs.keep_epochs > 0),
        passes_(hand_out_ ? 3 : 2),
        kept_(outputs.keep_epochs, source.size_hint()) {
    result_.options = o;
  }

  Result run() {
    read_until_moving();
    forward();
    check_line();
    backward();
    hand_out();
    report_progress(progress_, n_ * passes_, n_ * passes_, "done");
    summarise();
    result_.origin = source_.origin();
    for (std::string& n : source_.notes()) result_.notes.push_back(std::move(n));
    for (std::string& w : source_.warnings()) result_.warnings.push_back(std::move(w));
    result_.epochs = kept_.take();
    result_.epoch_stride = kept_.every();
    if (progress_) progress_->finish();
    return std::move(result_);
  }

 private:
  // The next chunk of the source into chunk_, chunk_truth_; false at the end.
  bool next_chunk() {
    if (source_.next(chunk_, chunk_truth_, kChunk) == 0) return false;
    if (have_truth_ && chunk_truth_.size() != chunk_.size())
      throw InputError(fmt::format("truth has {} entries for {} samples (give none or one per "
                                   "sample)",
                                   chunk_truth_.size(), chunk_.size()),
                       ErrorContext{{}, {}, "truth"});
    return true;
  }

  // Samples wait in pending_ until the reference speed of the initial x-variance is decided
  // (deflection.hpp: the median over the first reference_speed_window_s of motion), then
  // stream straight through. Bad samples are left for the forward pass to name.
  void read_until_moving() {
    ReferenceSpeed ref(stationary_threshold_m_s(o_), o_.stationary_min_duration_s,
                       o_.reference_speed_window_s);
    bool decided = false;
    while (!decided) {
      if (!next_chunk()) {
        exhausted_ = true;
        break;
      }
      pending_.insert(pending_.end(), chunk_.begin(), chunk_.end());
      pending_truth_.insert(pending_truth_.end(), chunk_truth_.begin(), chunk_truth_.end());
      for (const Sample& s : chunk_) {
        if (!std::isfinite(s.time_s) || !std::isfinite(s.speed_m_s) || s.speed_m_s < 0.0) {
          decided = true;  // the forward pass stops there with its error
          break;
        }
        if ((decided = ref.add(s.time_s, s.speed_m_s))) break;
      }
    }
    reference_speed_ = ref.value();
    result_.summary.reference_speed_m_s = reference_speed_;
  }

  // Pass 1: every sample through the filter; the epochs' forward outputs to epochs_.
  void forward() {
    layout_.full = hand_out_;
    layout_.truth = have_truth_;
    layout_.states =
        have_truth_ && !pending_truth_.empty() && pending_truth_.front().state.has_value();
    if (layout_.doubles() > 0)
      epochs_.emplace("MRDN-DVF", State::size, layout_.doubles(), o_.storage);
    fw_.emplace(o_, reference_speed_, result_, layout_, epochs_ ? &*epochs_ : nullptr);
    feed(pending_, pending_truth_);
    pending_ = {};
    pending_truth_ = {};
    while (!exhausted_ && next_chunk()) feed(chunk_, chunk_truth_);
    n_ = fw_->size();
  }

  void feed(const std::vector<Sample>& s, const std::vector<Truth>& t) {
    for (std::size_t i = 0; i < s.size(); ++i) {
      fw_->add(s[i], have_truth_ ? &t[i] : nullptr);
      if (fw_->size() % kProgressStride == 0)
        report_progress(progress_, fw_->size(), total_ * passes_, "filtering");
    }
  }

  // A line to smooth and epochs in its statistics.
  void check_line() {
    if (n_ < 2)
      throw InputError(fmt::format("a line needs at least 2 samples, has {}", n_),
                       ErrorContext{{}, {}, "samples"});
    result_.summary.epochs = n_;
    if (result_.summary.statistics_epochs == 0)
      throw InputError(fmt::format("options.statistics_start_s = {} s leaves no epoch in the "
                                   "statistics (the line lasts {} s)",
                                   o_.statistics_start_s, fw_->last_time() - fw_->t0()),
                       ErrorContext{{}, {}, "options.statistics_start_s"});
  }

  // Pass 2: the smoother, last epoch first, joined with each epoch's forward outputs; the
  // completed epochs to done_ (when they are handed out).
  void backward() {
    if (hand_out_) done_.emplace("MRDN-DVS", State::size, kRecordDoubles, o_.storage);
    std::optional<filter::detail::RecordStore::ReverseReader> forward_records;
    if (epochs_) forward_records.emplace(epochs_->read_reverse());
    // Time strictly increases, so the epochs with t − t₀ ≥ statistics_start_s are the last
    // statistics_epochs ones: the slim records need not carry the time.
    const std::size_t first_statistics_epoch = n_ - result_.summary.statistics_epochs;
    EpochResult e;
    StateVector state;
    std::size_t done = 0;
    filter::rts_smooth(fw_->storage(), [&](Eigen::Index k, const filter::Estimate<State::size>& sm) {
      if (forward_records) {
        const double* p = forward_records->next();
        if (layout_.full)
          unpack(p, e, &state);
        else
          unpack_slim(layout_, p, e, state);
      }
      smoothed(e, state, k, sm);
      if (static_cast<std::size_t>(k) >= first_statistics_epoch) accumulate_smoothed(e);
      if (k == 0) {
        result_.summary.eps_u_rad_s = e.smoothed.eps_u_rad_s;
        result_.summary.sigma_eps_u_rad_s = e.smoothed.sigma_eps_u_rad_s;
      }
      if (done_) pack(e, nullptr, done_->append(static_cast<std::uint64_t>(k)));
      if (++done % kProgressStride == 0)
        report_progress(progress_, n_ + done, n_ * passes_, "smoothing");
    });
  }

  // The smoothed estimate of epoch k (and its NEES with the true state).
  void smoothed(EpochResult& e, const StateVector& state, Eigen::Index k,
                const filter::Estimate<State::size>& sm) const {
    e.smoothed.eta_rad = e.model_eta_rad + sm.x(State::delta_eta);
    e.smoothed.xi_rad = e.model_xi_rad + sm.x(State::delta_xi);
    e.smoothed.sigma_eta_rad = sm.sigma(State::delta_eta);
    e.smoothed.sigma_xi_rad = sm.sigma(State::delta_xi);
    e.smoothed.eps_u_rad_s = sm.x(State::eps_u);
    e.smoothed.sigma_eps_u_rad_s = sm.sigma(State::eps_u);
    if (fw_->have_states()) e.nees_smoothed = filter::nees<State::size>(state, sm, k);
  }

  void accumulate_smoothed(const EpochResult& e) {
    ss_eta_.add(e.smoothed.sigma_eta_rad * e.smoothed.sigma_eta_rad);
    ss_xi_.add(e.smoothed.sigma_xi_rad * e.smoothed.sigma_xi_rad);
    if (e.truth) {
      const auto sq = [](double v) { return v * v; };
      s_eta_.add(sq(e.smoothed.eta_rad - e.truth->eta_rad));
      s_xi_.add(sq(e.smoothed.xi_rad - e.truth->xi_rad));
    }
    if (fw_->have_states()) nees_s_.add(*e.nees_smoothed);
  }

  // Pass 3: the epochs in time order (the last record of the backward pass is epoch 0) to the
  // sink and to the kept epochs.
  void hand_out() {
    if (!done_) return;
    auto reader = done_->read_reverse();
    EpochResult e;
    std::size_t k = 0;
    while (const double* p = reader.next()) {
      unpack(p, e, nullptr);
      if (outputs_.sink) outputs_.sink(e);
      kept_.add(e);
      if (++k % kProgressStride == 0)
        report_progress(progress_, 2 * n_ + k, 3 * n_, "writing");
    }
  }

  // The summary's statistics, its warnings (NIS, transport rate, gate) and notes.
  void summarise() {
    Summary& sum = result_.summary;
    const Forward& fw = *fw_;
    sum.mean_nis = fw.nis_.mean();
    if (fw.nis_.n > 0) {
      sum.nis_interval =
          filter::average_interval(Obs::size, static_cast<std::int64_t>(fw.nis_.n), 0.95);
      if (!sum.nis_interval.contains(sum.mean_nis))
        result_.warnings.push_back(fmt::format(
            "mean NIS {:.3f} is outside its 95 % interval [{:.3f}, {:.3f}]: the noise model "
            "(σ_model, r, P₀) does not fit the data",
            sum.mean_nis, sum.nis_interval.lower, sum.nis_interval.upper));
    }
    if (o_.transport_rate && sum.transport_rate_updates == 0)
      result_.warnings.push_back(fmt::format(
          "transport_rate: no baseline of {} s closed within the line ({} s): ω_en stayed 0, so "
          "the line was processed with the Earth-rate model (give a shorter "
          "transport_rate_baseline_s)",
          o_.transport_rate_baseline_s, fw.last_time() - fw.t0()));
    warn_about_the_gate();
    sum.whiteness = fw.whiteness().result(o_.whiteness_alpha);
    if (!sum.whiteness.pass)
      result_.warnings.push_back(fmt::format(
          "the normalised innovations are not white: Ljung–Box Q = {:.1f} > {:.1f} (χ²({:g}) at "
          "alpha = {:g}, {} lags, p = {:.2g}): the observation noise is correlated in time (e.g. "
          "a Gauss–Markov INS/GNSS attitude error) or the model misses a dynamic, and the σ "
          "are then optimistic",
          sum.whiteness.q, sum.whiteness.critical_value, sum.whiteness.dof, o_.whiteness_alpha,
          sum.whiteness.lags, sum.whiteness.p_value));
    sum.stationary_speed_m_s = fw.stationary_threshold();
    sum.stationary_from_speed_sigma = o_.speed_sigma_m_s > 0.0;
    sum.stationary_steps = fw.stationary_steps();
    sum.rms_sigma_filtered = {fw.sf_eta_.rms(), fw.sf_xi_.rms()};
    sum.rms_sigma_smoothed = {ss_eta_.rms(), ss_xi_.rms()};
    if (have_truth_) {
      sum.rms_model = EtaXi{fw.m_eta_.rms(), fw.m_xi_.rms()};
      sum.rms_filtered = EtaXi{fw.f_eta_.rms(), fw.f_xi_.rms()};
      sum.rms_smoothed = EtaXi{s_eta_.rms(), s_xi_.rms()};
    }
    if (fw.have_states()) {
      sum.mean_nees_filtered = fw.nees_f_.mean();
      sum.mean_nees_smoothed = nees_s_.mean();
    }
    if (fw.stationary_steps() > 0)
      result_.notes.push_back(fmt::format(
          "{} of {} steps stationary (V < {} m/s for at least {} s): δη, δξ held constant, "
          "x_E, x_N frozen; "
          "standing still η is not observable (the direction (φ_N, φ_U, δη) += c·(1, tan L, 1) "
          "leaves every observation unchanged), so while the carrier stands its σ(η) stays near "
          "the model's and η̂ may be no better than η_G",
          fw.stationary_steps(), n_ - 1, fw.stationary_threshold(),
          o_.stationary_min_duration_s));
  }

  // The mean NIS is over the accepted updates only, so a gate that rejects far more than its
  // α·N can hide a misfit there: say so (α·N plus 3 binomial σ plus 2).
  void warn_about_the_gate() {
    if (!(o_.gate_alpha > 0.0)) return;
    const std::size_t rejected = result_.summary.rejected;
    const double expected = o_.gate_alpha * static_cast<double>(n_);
    const double limit = expected + 3.0 * std::sqrt(expected * (1.0 - o_.gate_alpha)) + 2.0;
    if (static_cast<double>(rejected) > limit)
      result_.warnings.push_back(fmt::format(
          "the innovation gate rejected {} of {} updates, about {:.0f} expected at alpha = {:g}: "
          "the noise model (sigma_model, r, P0) does not fit the data or the line has blunders; "
          "the mean NIS above is over the accepted updates only",
          rejected, n_, expected, o_.gate_alpha));
  }

  SampleSource& source_;
  const Options& o_;
  const EpochOutputs& outputs_;
  Progress* progress_;
  const bool have_truth_;
  const std::size_t total_;  // samples, 0: unknown
  const bool hand_out_;      // a sink or kept epochs: pass 3
  const std::size_t passes_;
  Result result_;
  KeptEpochs kept_;
  std::vector<Sample> pending_, chunk_;
  std::vector<Truth> pending_truth_, chunk_truth_;
  bool exhausted_ = false;
  double reference_speed_ = 0.0;
  EpochLayout layout_;
  std::optional<filter::detail::RecordStore> epochs_, done_;
  std::optional<Forward> fw_;
  std::size_t n_ = 0;
  Accumulator ss_eta_, ss_xi_, s_eta_, s_xi_, nees_s_;
};

/// The samples of an Input, one chunk.
class VectorSource final : public SampleSource {
 public:
  explicit VectorSource(const Input& in) : in_(in) {}
  std::size_t next(std::vector<Sample>& samples, std::vector<Truth>& truth,
                   std::size_t max) override {
    const std::size_t n = std::min(max, in_.samples.size() - at_);
    samples.assign(in_.samples.begin() + static_cast<std::ptrdiff_t>(at_),
                   in_.samples.begin() + static_cast<std::ptrdiff_t>(at_ + n));
    truth.clear();
    if (!in_.truth.empty())
      truth.assign(in_.truth.begin() + static_cast<std::ptrdiff_t>(at_),
                   in_.truth.begin() + static_cast<std::ptrdiff_t>(at_ + n));
    at_ += n;
    return n;
  }
  bool has_truth() const override { return !in_.truth.empty(); }
  std::optional<std::size_t> size_hint() const override { return in_.samples.size(); }
  Origin origin() const override { return in_.origin; }

 private:
  const Input& in_;
  std::size_t at_ = 0;
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
  require_option(std::isfinite(o.transport_rate_baseline_s) && o.transport_rate_baseline_s > 0.0,
                 "transport_rate_baseline_s", "finite and > 0", o.transport_rate_baseline_s);
  require_option(o.gate_alpha == 0.0 || (o.gate_alpha > 0.0 && o.gate_alpha < 1.0), "gate_alpha",
                 "0 (no gate) or in (0, 1)", o.gate_alpha);
  require_option(std::isfinite(o.statistics_start_s) && o.statistics_start_s >= 0.0,
                 "statistics_start_s", "finite and ≥ 0", o.statistics_start_s);
  require_option(std::isfinite(o.speed_sigma_m_s) && o.speed_sigma_m_s >= 0.0, "speed_sigma_m_s",
                 "finite and ≥ 0", o.speed_sigma_m_s);
  require_option(std::isfinite(o.stationary_sigma_factor) && o.stationary_sigma_factor > 0.0,
                 "stationary_sigma_factor", "finite and > 0", o.stationary_sigma_factor);
  require_option(std::isfinite(o.stationary_min_duration_s) && o.stationary_min_duration_s >= 0.0,
                 "stationary_min_duration_s", "finite and ≥ 0", o.stationary_min_duration_s);
  require_option(std::isfinite(o.reference_speed_window_s) && o.reference_speed_window_s > 0.0,
                 "reference_speed_window_s", "finite and > 0", o.reference_speed_window_s);
  require_option(o.whiteness_alpha > 0.0 && o.whiteness_alpha < 1.0, "whiteness_alpha",
                 "in (0, 1)", o.whiteness_alpha);
  require_option(o.whiteness_max_lag >= 1 && o.whiteness_max_lag <= 1000, "whiteness_max_lag",
                 "in [1, 1000]", o.whiteness_max_lag);
}

double stationary_threshold_m_s(const Options& o) {
  return o.speed_sigma_m_s > 0.0 ? o.stationary_sigma_factor * o.speed_sigma_m_s
                                 : o.model.stationary_speed_m_s;
}

Result process_stream(SampleSource& source, const Options& options, const EpochOutputs& outputs,
                      Progress* progress) {
  validate(options);
  return LineRun(source, options, outputs, progress).run();
}

Result process(const Input& input, Progress* progress) {
  validate(input.options);
  if (!input.truth.empty() && input.truth.size() != input.samples.size())
    throw InputError(fmt::format("truth has {} entries for {} samples (give none or one per "
                                 "sample)",
                                 input.truth.size(), input.samples.size()),
                     ErrorContext{{}, {}, "truth"});
  VectorSource source(input);
  return process_stream(source, input.options, EpochOutputs{{}, kAllEpochs}, progress);
}

}  // namespace meridian::dov
