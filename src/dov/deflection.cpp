#include "meridian/dov/deflection.hpp"

#include <algorithm>
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

/// The forward pass of process_stream: one sample at a time.
class Forward {
 public:
  /// `epochs` receives each epoch in `layout` (nullptr when it has no doubles).
  Forward(const Options& o, double reference_speed, LineResult& out, EpochLayout layout,
          filter::detail::RecordStore* epochs)
      : o_(o),
        H_(observation_matrix()),
        R_(observation_covariance(o.sigma_obs_east_rad, o.sigma_obs_north_rad)),
        kf_(initial_estimate(o.initial, o.model, reference_speed),
            o.gate_alpha > 0.0 ? filter::InnovationGate(o.gate_alpha) : filter::InnovationGate()),
        storage_(State::size, o.storage),
        layout_(layout),
        epochs_(epochs),
        out_(out) {
    kf_.set_transition_kernel(&kTransitionKernel);
    if (!o.initial.x_rad_s)
      out.notes.push_back(
          reference_speed > 0.0
              ? fmt::format("initial σ of x_E, x_N: σ_model/ω₀ at the first moving speed {} m/s",
                            reference_speed)
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
    if (truth) {
      const auto field = [&](const char* m) { return fmt::format("truth[{}].{}", k, m); };
      if (!std::isfinite(truth->eta_rad) || !std::isfinite(truth->xi_rad))
        throw InputError("true deflection is not finite", ErrorContext{{}, {}, field("eta_rad")});
      if (truth->state && !truth->state->allFinite())
        throw InputError("true state is not finite", ErrorContext{{}, {}, field("state")});
      if (k == 0) have_states_ = truth->state.has_value();
      if (truth->state.has_value() != have_states_)
        throw InputError("a true state is given for some samples only",
                         ErrorContext{{}, {}, field("state")});
    }
    check_sample(s, k, o_);
    if (k > 0) {
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
      const double speed = 0.5 * (s.speed_m_s + prev_speed_);
      const bool stationary = is_stationary(speed, o_.model);
      if (stationary) ++stationary_steps_;
      if (o_.transport_rate && s.time_s - baseline_time_ >= o_.transport_rate_baseline_s) {
        // Options::transport_rate: the mean rates over the baseline that closes here.
        const double span = s.time_s - baseline_time_;
        const double dlon = std::remainder(s.lon_rad - baseline_lon_, 2.0 * units::kPi);
        transport_rate_ = transport_rate(0.5 * (s.lat_rad + baseline_lat_),
                                         (s.lat_rad - baseline_lat_) / span, dlon / span);
        baseline_time_ = s.time_s;
        baseline_lat_ = s.lat_rad;
        baseline_lon_ = s.lon_rad;
        ++out_.summary.transport_rate_updates;
      }
      if (!cache_.valid || std::abs(dt - cache_.dt_s) > o_.step_tolerance * cache_.dt_s ||
          std::abs(lat - cache_.lat_rad) > o_.rediscretise_latitude_rad ||
          std::abs(speed - cache_.speed_m_s) > o_.rediscretise_speed_m_s ||
          stationary != cache_.stationary || transport_rate_ != cache_.transport_rate_rad_s) {
        cache_.step =
            discrete_model(lat, speed, dt, o_.model, o_.discretisation, transport_rate_);
        cache_.valid = true;
        cache_.dt_s = dt;
        cache_.lat_rad = lat;
        cache_.speed_m_s = speed;
        cache_.stationary = stationary;
        cache_.transport_rate_rad_s = transport_rate_;
        ++out_.summary.discretisations;
      }
      kf_.predict(cache_.step);
    } else {
      t0_ = s.time_s;
      baseline_time_ = s.time_s;
      baseline_lat_ = s.lat_rad;
      baseline_lon_ = s.lon_rad;
    }
    const Eigen::Matrix3d c = attitude_difference_matrix(s.lgu_body_to_nav, s.ins_body_to_nav);
    // Both matrices make the difference: the error names neither one alone.
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
    filter::Vector<Obs::size> y;
    y(Obs::east) = d.east_rad - s.model_xi_rad;
    y(Obs::north) = d.north_rad + s.model_eta_rad;
    const filter::Innovation<Obs::size> in = kf_.update(y, H_, R_);
    storage_.append(kf_);  // compact records: P⁻ recomputed when read back

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
    if (!in.accepted) ++out_.summary.rejected;
    if (have_states_)
      e.nees_filtered = filter::nees<State::size>(*truth->state, kf_.estimate(),
                                                  static_cast<Eigen::Index>(k));
    if (layout_.full)
      pack(e, have_states_ ? &*truth->state : nullptr, epochs_->append(k));
    else if (epochs_)
      pack_slim(layout_, s, truth, epochs_->append(k));

    // Forward statistics.
    if (s.time_s - t0_ >= o_.statistics_start_s) {
      ++out_.summary.statistics_epochs;
      if (e.accepted) nis_.add(e.nis);
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

  Accumulator nis_, sf_eta_, sf_xi_, m_eta_, m_xi_, f_eta_, f_xi_, nees_f_;

 private:
  const Options& o_;
  ObservationMatrix H_;
  ObservationCovariance R_;
  filter::KalmanFilter<State::size> kf_;
  filter::SmootherStorage<State::size> storage_;
  EpochLayout layout_;
  filter::detail::RecordStore* epochs_;
  LineResult& out_;
  ModelCache cache_;
  std::size_t n_ = 0;
  std::size_t stationary_steps_ = 0;
  bool have_states_ = false;
  double t0_ = 0.0, prev_time_ = 0.0, prev_lat_ = 0.0, prev_speed_ = 0.0;
  // Options::transport_rate: the open baseline's first sample and the current ω_en (ENU).
  double baseline_time_ = 0.0, baseline_lat_ = 0.0, baseline_lon_ = 0.0;
  Eigen::Vector3d transport_rate_ = Eigen::Vector3d::Zero();
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
}

LineResult process_stream(SampleSource& source, const Options& o, const EpochSink& sink,
                          Progress* progress) {
  validate(o);
  LineResult out;
  const bool have_truth = source.has_truth();
  const std::size_t total = source.size_hint().value_or(0);  // 0: unknown
  const auto progress_total = [&](std::size_t passes) { return total * passes; };
  const std::size_t passes = sink ? 3 : 2;

  // Samples wait here until the first moving one gives the reference speed of the initial
  // x-variance (a stationary start), then stream straight through.
  std::vector<Sample> pending, chunk;
  std::vector<Truth> pending_truth, chunk_truth;
  double reference_speed = 0.0;
  const auto moving = [&](const Sample& s) {
    return std::isfinite(s.speed_m_s) && s.speed_m_s >= 0.0 && !is_stationary(s.speed_m_s, o.model);
  };
  bool exhausted = false;
  for (;;) {
    if (source.next(chunk, chunk_truth, kChunk) == 0) {
      exhausted = true;
      break;
    }
    if (have_truth && chunk_truth.size() != chunk.size())
      throw InputError(fmt::format("truth has {} entries for {} samples (give none or one per "
                                   "sample)",
                                   chunk_truth.size(), chunk.size()),
                       ErrorContext{{}, {}, "truth"});
    pending.insert(pending.end(), chunk.begin(), chunk.end());
    pending_truth.insert(pending_truth.end(), chunk_truth.begin(), chunk_truth.end());
    const auto first = std::find_if(chunk.begin(), chunk.end(), moving);
    if (first != chunk.end()) {
      reference_speed = first->speed_m_s;
      break;
    }
  }

  EpochLayout layout;
  layout.full = static_cast<bool>(sink);
  layout.truth = have_truth;
  layout.states = have_truth && !pending_truth.empty() && pending_truth.front().state.has_value();
  std::optional<filter::detail::RecordStore> epochs;
  if (layout.doubles() > 0) epochs.emplace("MRDN-DVF", State::size, layout.doubles(), o.storage);
  Forward fw(o, reference_speed, out, layout, epochs ? &*epochs : nullptr);
  const auto feed = [&](const std::vector<Sample>& s, const std::vector<Truth>& t) {
    for (std::size_t i = 0; i < s.size(); ++i) {
      fw.add(s[i], have_truth ? &t[i] : nullptr);
      if (fw.size() % kProgressStride == 0)
        report_progress(progress, fw.size(), progress_total(passes), "filtering");
    }
  };
  feed(pending, pending_truth);
  pending = {};
  pending_truth = {};
  while (!exhausted && source.next(chunk, chunk_truth, kChunk) > 0) {
    if (have_truth && chunk_truth.size() != chunk.size())
      throw InputError(fmt::format("truth has {} entries for {} samples (give none or one per "
                                   "sample)",
                                   chunk_truth.size(), chunk.size()),
                       ErrorContext{{}, {}, "truth"});
    feed(chunk, chunk_truth);
  }
  const std::size_t n = fw.size();
  if (n < 2)
    throw InputError(fmt::format("a line needs at least 2 samples, has {}", n),
                     ErrorContext{{}, {}, "samples"});
  Summary& sum = out.summary;
  sum.epochs = n;
  if (sum.statistics_epochs == 0)
    throw InputError(fmt::format("options.statistics_start_s = {} s leaves no epoch in the "
                                 "statistics (the line lasts {} s)",
                                 o.statistics_start_s, fw.last_time() - fw.t0()),
                     ErrorContext{{}, {}, "options.statistics_start_s"});

  // Backward: the smoother joined with each epoch's forward outputs.
  const bool have_states = fw.have_states();
  std::optional<filter::detail::RecordStore> done_store;
  if (sink) done_store.emplace("MRDN-DVS", State::size, kRecordDoubles, o.storage);
  Accumulator ss_eta, ss_xi, s_eta, s_xi, nees_s;
  std::optional<filter::detail::RecordStore::ReverseReader> forward_records;
  if (epochs) forward_records.emplace(epochs->read_reverse());
  // Time strictly increases, so the epochs with t − t₀ ≥ statistics_start_s are the last
  // statistics_epochs ones: the slim records need not carry the time.
  const std::size_t first_statistics_epoch = n - sum.statistics_epochs;
  EpochResult e;
  StateVector state;
  std::size_t done = 0;
  filter::rts_smooth(fw.storage(), [&](Eigen::Index k, const filter::Estimate<State::size>& sm) {
    if (forward_records) {
      const double* p = forward_records->next();
      if (layout.full)
        unpack(p, e, &state);
      else
        unpack_slim(layout, p, e, state);
    }
    e.smoothed.eta_rad = e.model_eta_rad + sm.x(State::delta_eta);
    e.smoothed.xi_rad = e.model_xi_rad + sm.x(State::delta_xi);
    e.smoothed.sigma_eta_rad = sm.sigma(State::delta_eta);
    e.smoothed.sigma_xi_rad = sm.sigma(State::delta_xi);
    e.smoothed.eps_u_rad_s = sm.x(State::eps_u);
    e.smoothed.sigma_eps_u_rad_s = sm.sigma(State::eps_u);
    if (have_states) e.nees_smoothed = filter::nees<State::size>(state, sm, k);
    if (static_cast<std::size_t>(k) >= first_statistics_epoch) {
      ss_eta.add(e.smoothed.sigma_eta_rad * e.smoothed.sigma_eta_rad);
      ss_xi.add(e.smoothed.sigma_xi_rad * e.smoothed.sigma_xi_rad);
      if (e.truth) {
        const auto sq = [](double v) { return v * v; };
        s_eta.add(sq(e.smoothed.eta_rad - e.truth->eta_rad));
        s_xi.add(sq(e.smoothed.xi_rad - e.truth->xi_rad));
      }
      if (have_states) nees_s.add(*e.nees_smoothed);
    }
    if (k == 0) {
      sum.eps_u_rad_s = e.smoothed.eps_u_rad_s;
      sum.sigma_eps_u_rad_s = e.smoothed.sigma_eps_u_rad_s;
    }
    if (done_store) pack(e, nullptr, done_store->append(static_cast<std::uint64_t>(k)));
    if (++done % kProgressStride == 0)
      report_progress(progress, n + done, n * passes, "smoothing");
  });

  // The epochs in time order: the last record of the backward pass is epoch 0.
  if (done_store) {
    auto reader = done_store->read_reverse();
    std::size_t k = 0;
    while (const double* p = reader.next()) {
      unpack(p, e, nullptr);
      sink(e);
      if (++k % kProgressStride == 0)
        report_progress(progress, 2 * n + k, 3 * n, "writing");
    }
  }
  report_progress(progress, n * passes, n * passes, "done");

  // Summary.
  sum.mean_nis = fw.nis_.mean();
  if (fw.nis_.n > 0) {
    sum.nis_interval =
        filter::average_interval(Obs::size, static_cast<std::int64_t>(fw.nis_.n), 0.95);
    if (!sum.nis_interval.contains(sum.mean_nis))
      out.warnings.push_back(fmt::format(
          "mean NIS {:.3f} is outside its 95 % interval [{:.3f}, {:.3f}]: the noise model "
          "(σ_model, r, P₀) does not fit the data",
          sum.mean_nis, sum.nis_interval.lower, sum.nis_interval.upper));
  }
  if (o.transport_rate && sum.transport_rate_updates == 0)
    out.warnings.push_back(fmt::format(
        "transport_rate: no baseline of {} s closed within the line ({} s): ω_en stayed 0, so the "
        "line was processed with the Earth-rate model (give a shorter "
        "transport_rate_baseline_s)",
        o.transport_rate_baseline_s, fw.last_time() - fw.t0()));
  // The mean NIS is over the accepted updates only, so a gate that rejects far more than its
  // α·N can hide a misfit there: say so (α·N plus 3 binomial σ plus 2).
  if (o.gate_alpha > 0.0) {
    const double expected = o.gate_alpha * static_cast<double>(n);
    const double limit = expected + 3.0 * std::sqrt(expected * (1.0 - o.gate_alpha)) + 2.0;
    if (static_cast<double>(sum.rejected) > limit)
      out.warnings.push_back(fmt::format(
          "the innovation gate rejected {} of {} updates, about {:.0f} expected at alpha = {:g}: "
          "the noise model (sigma_model, r, P0) does not fit the data or the line has blunders; "
          "the mean NIS above is over the accepted updates only",
          sum.rejected, n, expected, o.gate_alpha));
  }
  sum.rms_sigma_filtered = {fw.sf_eta_.rms(), fw.sf_xi_.rms()};
  sum.rms_sigma_smoothed = {ss_eta.rms(), ss_xi.rms()};
  if (have_truth) {
    sum.rms_model = EtaXi{fw.m_eta_.rms(), fw.m_xi_.rms()};
    sum.rms_filtered = EtaXi{fw.f_eta_.rms(), fw.f_xi_.rms()};
    sum.rms_smoothed = EtaXi{s_eta.rms(), s_xi.rms()};
  }
  if (have_states) {
    sum.mean_nees_filtered = fw.nees_f_.mean();
    sum.mean_nees_smoothed = nees_s.mean();
  }
  if (fw.stationary_steps() > 0)
    out.notes.push_back(fmt::format(
        "{} of {} steps stationary (V < {} m/s): δη, δξ held constant, x_E, x_N frozen; "
        "standing still η is not observable (the direction (φ_N, φ_U, δη) += c·(1, tan L, 1) "
        "leaves every observation unchanged), so while the carrier stands its σ(η) stays near "
        "the model's and η̂ may be no better than η_G",
        fw.stationary_steps(), n - 1, o.model.stationary_speed_m_s));
  if (progress) progress->finish();
  return out;
}

Result process(const Input& input, Progress* progress) {
  validate(input.options);
  if (!input.truth.empty() && input.truth.size() != input.samples.size())
    throw InputError(fmt::format("truth has {} entries for {} samples (give none or one per "
                                 "sample)",
                                 input.truth.size(), input.samples.size()),
                     ErrorContext{{}, {}, "truth"});
  VectorSource source(input);
  Result result;
  result.epochs.reserve(input.samples.size());
  LineResult line = process_stream(
      source, input.options, [&](const EpochResult& e) { result.epochs.push_back(e); }, progress);
  result.summary = line.summary;
  result.notes = std::move(line.notes);
  result.warnings = std::move(line.warnings);
  return result;
}

}  // namespace meridian::dov
