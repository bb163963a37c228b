#pragma once
/// \file deflection.hpp
/// The dynamic deflection-of-the-vertical workflow (shared/spec/deflection.md; docs/deflection.md):
/// per sample the two attitude solutions of a moving carrier and the global model's deflection,
/// a Kalman filter over the 8-state model (model.hpp) and a Rauch–Tung–Striebel smoother over
/// the whole line (filter module), giving per epoch η, ξ filtered and smoothed with σ.
///
///   Input (samples, optional truth, Options) → process() → Result (epochs, summary)
///   SampleSource (a line of any length) → process_stream() → EpochSink, Result (streaming.hpp)
///
/// Per sample k (epoch k of the filter; epoch 0 is the first sample):
///  1. checks: time finite and strictly increasing, step ≤ Options::max_step_s; position
///     finite with |lat| ≤ π/2; speed finite and ≥ 0; η_G, ξ_G finite (a missing model value
///     is an error, never NaN output); both attitude matrices finite, orthogonal within
///     Options::orthogonality_tolerance and proper (attitude_difference.hpp);
///  2. C = C_b^n·(C_b^{n′})ᵀ and ΔΦ (Options::extraction), |ΔΦ| ≤ max_attitude_difference_rad;
///  3. k > 0: predict with the model discretised over t_k − t_{k−1} at the mean latitude and
///     speed of the step; the model is re-discretised only when the step length changes by
///     more than step_tolerance (relative), the latitude by more than rediscretise_latitude_rad,
///     the speed by more than rediscretise_speed_m_s, or the carrier starts or stops
///     (model.hpp: stationary case); otherwise the last Φ, Q_d are reused. Stationary or
///     moving (stops, below): the class after sample k, with hysteresis;
///  4. update with y = [ΔΦ_E − ξ_G, ΔΦ_N + η_G]ᵀ, H and R of model.hpp (Joseph form,
///     filter/kalman_filter.hpp), optional χ² gate;
///  5. η̂ = η_G + δη̂, ξ̂ = ξ_G + δξ̂ with σ(η̂) = σ(δη̂), σ(ξ̂) = σ(δξ̂) (the model values carry
///     no σ of their own: their error is the state δ).
/// Then the RTS smoother (filter/rts_smoother.hpp; its records spill to a temporary file for
/// long lines, filter::StorageOptions) gives the smoothed values of every epoch.
///
/// Summary statistics over the epochs with t − t₀ ≥ Options::statistics_start_s (all by
/// default): mean NIS with its exact 95 % χ² interval (innovations of a correct model are
/// white), the quadratic mean of the reported σ, and — when truth is given — the RMS errors of
/// the model, filtered and smoothed deflections and the mean NEES (8 states) when the full true
/// state is given.
///
/// Stops. GNSS speed over ground is noisy (a few cm/s at rest), so one sample's speed does not
/// decide whether the carrier stands. The threshold V_s is stationary_threshold_m_s(options):
/// ModelOptions::stationary_speed_m_s (default 0.1 m/s, model.hpp), or, when the line's speed
/// σ is known (Options::speed_sigma_m_s > 0), stationary_sigma_factor·σ_v (4σ: a Rayleigh
/// speed at rest exceeds it in 3·10⁻⁴ of samples). The class changes only when the speed has
/// stayed on the other side of V_s for at least stationary_min_duration_s (5 s; 0: at once),
/// from the first sample on that side to the current one; sample 0 sets the first class. A
/// step classed stationary is predicted with the stationary model (V = 0); a step classed
/// moving with the moving model at max(V, V_s) (the speed of a carrier that is slowing down
/// before the stop is confirmed). A noise spike above V_s during a stop, or a dip below it in
/// motion, therefore changes nothing; the cost is that a real start or stop is taken up to
/// 5 s late, a few metres of travel against the 10 km correlation length.
///
/// Reference speed of P₀ (model.hpp, initial_estimate: σ(x) = σ_model/ω₀(V_ref)): the median
/// speed of the samples with V ≥ V_s in the first reference_speed_window_s (300 s) of motion,
/// where motion begins with the first run of samples at V ≥ V_s that lasts
/// stationary_min_duration_s (or reaches the end of the line). So a line that starts at rest
/// and accelerates takes its cruising speed, not the first sample that crossed V_s; a line
/// without such a run is stationary (σ(x) = σ_model·1 s). Summary::reference_speed_m_s.
///
/// Whiteness. The normalised innovations e_k = L_k⁻¹·ν_k (S_k = L_k·L_kᵀ, Cholesky; two
/// independent N(0, 1) series for a correct model) of the accepted statistics epochs are
/// tested by Ljung–Box (filter/whiteness.hpp) with h = min(whiteness_max_lag, ⌊n/5⌋) lags
/// (20 by default), Q summed over the two components, χ²(2h) at whiteness_alpha (0.05);
/// a warning when it fails. A time-correlated attitude noise the model does not have (e.g. a
/// Gauss–Markov INS/GNSS error with a correlation time of 10–60 s) fails it even when its
/// variance, and so the mean NIS, fits. Summary::whiteness.
///
/// Memory: process(const Input&) holds the Input and the per-epoch Result (≈ 200 bytes per
/// epoch each); it runs the streaming form, process_stream (streaming.hpp), over them, which
/// holds neither: use that for very long lines.
///
/// Errors: InputError with field "samples[k].<member>" (time_s, lat_rad, lon_rad, height_m,
/// speed_m_s, model_eta_rad, model_xi_rad, lgu_body_to_nav, ins_body_to_nav) or
/// "truth[k].<member>", or "options.<name>" for an option out of range; errors from the filter
/// (filter/kalman_filter.hpp: NumericalError for a covariance that is no longer positive
/// definite) name "epoch k", which is samples[k]; IoError when the smoother's spill file fails.
/// No output is NaN.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "meridian/core/progress.hpp"
#include "meridian/core/units.hpp"
#include "meridian/dov/attitude_difference.hpp"
#include "meridian/dov/model.hpp"
#include "meridian/filter/consistency.hpp"
#include "meridian/filter/detail/record_store.hpp"
#include "meridian/filter/whiteness.hpp"

namespace meridian::dov {

/// One sample of the line. Units SI and radians; frames attitude_difference.hpp.
struct Sample {
  double time_s = 0.0;    ///< strictly increasing along the line (s)
  double lat_rad = 0.0;   ///< geodetic latitude, |lat| ≤ π/2
  double lon_rad = 0.0;   ///< longitude, east positive
  double height_m = 0.0;  ///< ellipsoidal height (m)
  double speed_m_s = 0.0; ///< carrier speed over ground 0 ≤ V ≤ kMaxSpeed_m_s (m/s); sets ω₀ = 2πV/λ
  Eigen::Matrix3d lgu_body_to_nav = Eigen::Matrix3d::Identity();  ///< C_b^n, LGU/GNSS
  Eigen::Matrix3d ins_body_to_nav = Eigen::Matrix3d::Identity();  ///< C_b^{n′}, INS/GNSS
  /// η_G of the global model at the sample (rad), |η_G| ≤ geodesy::kMaxDeflection_rad (34′).
  double model_eta_rad = 0.0;
  double model_xi_rad = 0.0;   ///< ξ_G (rad), |ξ_G| ≤ geodesy::kMaxDeflection_rad
};

/// Largest accepted carrier speed (m/s): above any ship, vehicle or aircraft that carries the
/// method; larger values are a unit error.
inline constexpr double kMaxSpeed_m_s = 1000.0;

/// Known truth of a sample (simulations): the deflection, and optionally the full 8-state.
struct Truth {
  double eta_rad = 0.0;  ///< true η (rad)
  double xi_rad = 0.0;   ///< true ξ (rad)
  /// True state [φ_E, φ_N, φ_U, ε_U, x_E, x_N, δη, δξ] (model.hpp units) for the NEES.
  std::optional<StateVector> state;
};

/// Options, spec defaults. Every angle in radians.
struct Options {
  ModelOptions model;
  InitialSigmas initial;
  DiscretisationMethod discretisation = DiscretisationMethod::Exact;
  Extraction extraction = Extraction::Exact;
  double sigma_obs_east_rad = 0.5 * units::kArcsecond;   ///< √r_E, INS/GNSS noise on ΔΦ_E, > 0
  double sigma_obs_north_rad = 0.5 * units::kArcsecond;  ///< √r_N, > 0
  double orthogonality_tolerance = kOrthogonalityTolerance;  ///< check_rotation, > 0
  double max_attitude_difference_rad = units::kDegree;       ///< |ΔΦ| above this: InputError
  double max_step_s = 60.0;                 ///< a longer step between samples is an InputError
  double step_tolerance = 1e-6;             ///< relative change of Δt that re-discretises
  double rediscretise_latitude_rad = 0.01 * units::kDegree;  ///< ≥ 0
  double rediscretise_speed_m_s = 0.01;                      ///< ≥ 0
  /// Transport rate ω_en in the attitude dynamics (model.hpp): false is the spec's Earth-rate
  /// model. When true, ω_en = (−L̇, λ̇·cos L, λ̇·sin L) from the track itself: the mean rates of
  /// latitude and longitude between the sample that closes a baseline of at least
  /// transport_rate_baseline_s and the sample that opened it, held until the next baseline
  /// closes (zero until the first one does). A baseline rather than consecutive samples because
  /// GNSS position noise differentiated over 0.01 s would dwarf ω_en; 10 s of a moving carrier
  /// give its mean over 10 s, lagging by about half of it.
  bool transport_rate = false;
  double transport_rate_baseline_s = 10.0;  ///< > 0 (s)
  double gate_alpha = 0.0;  ///< χ² innovation gate at significance α in (0, 1); 0: no gate
  double statistics_start_s = 0.0;  ///< summary over t − t₀ ≥ this (s), ≥ 0
  filter::StorageOptions storage;   ///< where the smoother's records spill
  /// σ of the line's GNSS speed over ground per horizontal component (m/s), ≥ 0; 0: not known.
  /// When > 0 the stationary threshold is stationary_sigma_factor·σ_v instead of
  /// model.stationary_speed_m_s (file comment, Stops).
  double speed_sigma_m_s{0.0};
  double stationary_sigma_factor{4.0};    ///< k of k·σ_v, > 0
  double stationary_min_duration_s{5.0};  ///< hysteresis of the stop/start class (s), ≥ 0
  double reference_speed_window_s{300.0};  ///< motion that sets P₀'s reference speed (s), > 0
  double whiteness_alpha{0.05};  ///< significance of the Ljung–Box test, in (0, 1)
  int whiteness_max_lag{20};     ///< its lags h = min(this, ⌊n/5⌋), in [1, 1000]
};

/// The stationary threshold the workflow uses (m/s): stationary_sigma_factor·speed_sigma_m_s
/// when speed_sigma_m_s > 0, else model.stationary_speed_m_s.
double stationary_threshold_m_s(const Options& options);

/// Where a line came from, as its writers name it (the report's header): text only, set by
/// whoever made the line — io's runner from the configuration, the line file and the gravity
/// model it names (io/dov_jobs.hpp), a caller with a line made in memory by a description.
/// Empty members are not known.
struct Origin {
  std::string input;  ///< the configuration file, or what made a line in memory
  std::string line;   ///< the line file; empty: `input` itself
  std::string model;  ///< what gave η_G, ξ_G ("egm96 (to degree 360)"); empty: the line's values
};

struct Input {
  std::vector<Sample> samples;  ///< at least 2
  std::vector<Truth> truth;     ///< empty, or one per sample
  Options options;
  Origin origin;  ///< copied into Result::origin
};

/// A deflection estimate of one epoch (filtered or smoothed).
struct DeflectionEstimate {
  double eta_rad = 0.0;          ///< η̂ = η_G + δη̂
  double xi_rad = 0.0;           ///< ξ̂ = ξ_G + δξ̂
  double sigma_eta_rad = 0.0;    ///< σ(δη̂)
  double sigma_xi_rad = 0.0;     ///< σ(δξ̂)
  double eps_u_rad_s = 0.0;      ///< ε̂_U (rad/s)
  double sigma_eps_u_rad_s = 0.0;
};

/// η and ξ of one statistic (rad).
struct EtaXi {
  double eta_rad = 0.0;
  double xi_rad = 0.0;
};

struct EpochResult {
  double time_s = 0.0;
  double lat_rad = 0.0;        ///< the sample's geodetic latitude
  double lon_rad = 0.0;        ///< the sample's longitude, east positive
  double model_eta_rad = 0.0;  ///< η_G
  double model_xi_rad = 0.0;   ///< ξ_G
  AttitudeDifference observed;  ///< ΔΦ of the sample
  DeflectionEstimate filtered;  ///< observations 0…k
  DeflectionEstimate smoothed;  ///< the whole line
  double innovation_east_rad = 0.0;   ///< ν_E = y_E − (H·x̂⁻)_E
  double innovation_north_rad = 0.0;  ///< ν_N
  double sigma_innovation_east_rad = 0.0;   ///< √S_EE
  double sigma_innovation_north_rad = 0.0;  ///< √S_NN
  double nis = 0.0;                   ///< νᵀS⁻¹ν (2 degrees of freedom)
  bool accepted = true;               ///< false: rejected by the gate (no update)
  std::optional<double> nees_filtered;  ///< with a true state
  std::optional<double> nees_smoothed;
  std::optional<EtaXi> truth;  ///< the true η, ξ when Input::truth is given (simulations)
};

struct Summary {
  std::size_t epochs = 0;             ///< samples processed
  std::size_t statistics_epochs = 0;  ///< epochs in the statistics (t − t₀ ≥ statistics_start_s)
  std::size_t rejected = 0;           ///< updates rejected by the gate (all epochs)
  std::size_t discretisations = 0;    ///< times the model was discretised
  /// Options::transport_rate: baselines closed, i.e. times ω_en was set (0: ω_en stayed 0,
  /// the Earth-rate model, and a warning says so).
  std::size_t transport_rate_updates = 0;
  /// Over the accepted statistics epochs; a warning says when the gate rejected far more
  /// than α·N (3 binomial σ + 2 above it), which this mean then cannot show.
  double mean_nis = 0.0;
  filter::ChiSquaredInterval nis_interval;  ///< 95 % interval of mean_nis for a correct model
  EtaXi rms_sigma_filtered;  ///< √(mean σ²) of the filtered η̂, ξ̂
  EtaXi rms_sigma_smoothed;  ///< √(mean σ²) of the smoothed
  std::optional<EtaXi> rms_model;     ///< RMS(η_G − η), RMS(ξ_G − ξ), with truth
  std::optional<EtaXi> rms_filtered;  ///< RMS(η̂ − η), … filtered, with truth
  std::optional<EtaXi> rms_smoothed;  ///< smoothed, with truth
  std::optional<double> mean_nees_filtered;  ///< with true states (8 degrees of freedom)
  std::optional<double> mean_nees_smoothed;
  double eps_u_rad_s = 0.0;        ///< smoothed ε̂_U (a constant: the value at epoch 0)
  double sigma_eps_u_rad_s = 0.0;  ///< its σ
  /// The stationary threshold used (stationary_threshold_m_s) and whether it came from
  /// Options::speed_sigma_m_s.
  double stationary_speed_m_s{0.0};
  bool stationary_from_speed_sigma{false};
  std::size_t stationary_steps{0};  ///< steps classed stationary (of epochs − 1)
  /// The speed of P₀'s σ(x) (file comment); 0: no motion, the line is stationary.
  double reference_speed_m_s{0.0};
  /// Ljung–Box on the normalised innovations of the accepted statistics epochs (lags 0: fewer
  /// than 5 of them, not tested).
  filter::LjungBoxResult whiteness{};
};

/// The result of a line, self-describing: with the options and origin the writers show.
struct Result {
  Options options;  ///< the options the line was processed with
  Origin origin;    ///< where the line came from (Input::origin, SampleSource::origin)
  /// process(): one per sample, in time order. A streamed line (process_stream): the epochs
  /// EpochOutputs::keep_epochs asks for — none, all, or every epoch_stride-th one.
  std::vector<EpochResult> epochs;
  std::size_t epoch_stride = 1;  ///< epochs holds epoch 0, epoch_stride, 2·epoch_stride, …
  Summary summary;
  std::vector<std::string> notes;     ///< defaults used, stationary epochs; the source's last
  std::vector<std::string> warnings;  ///< e.g. NIS outside its interval; the source's last
};

/// Throws InputError (field "options.<name>") unless every option is in range.
void validate(const Options& options);

/// Run filter and smoother over the line (file comment): process_stream over the Input's
/// vectors, every epoch kept in Result::epochs.
Result process(const Input& input, Progress* progress = nullptr);

}  // namespace meridian::dov
