#pragma once
/// \file navigation.hpp
/// The marine navigation post-processing workflow (shared/spec/navigation.md;
/// docs/navigation.md): dead reckoning, lines of position, satellite fixes → the best track
/// with σ, blunders rejected, the DR velocity bias estimated; the classical sequential
/// adjustment and its variants beside an EKF and its RTS smoother, on the same data.
///
///   Input (DR, stations, chains, LOPs, fixes, optional truth, Options) → process() → Result
///
/// Epochs: one per DR sample (its time_s); epoch 0 is the first sample, where the initial
/// position applies. Every LOP and fix is reduced to the DR epoch nearest in time (spec §3: the
/// DR increment between them is added to the computed value and its variance to the
/// observation's). An observation up to Options::max_reduction_s before the first or after
/// the last epoch is reduced to that epoch with the first or last sample's velocity; one
/// farther than max_reduction_s from every epoch is skipped and listed in Result::skipped.
///
/// The state of the sequential methods is the position (x, y) plus the chain parameters
/// (spec §4.3); of the EKF also the velocity bias W = (W_N, W_E) (m/s), the correction to add
/// to the DR velocity: v_true = v_DR + W. DR increments: Δ_k = (t_k − t_{k−1})·v_k with
/// covariance (t_k − t_{k−1})²·Σ_v,k.
///
/// Errors: InputError with field "dr[k].<member>", "lops[k].<member>", "fixes[k].<member>",
/// "stations[k].<member>", "chains[k].<member>", "truth[k].<member>", "initial.<member>" or
/// "options.<name>"; NumericalError (from the filter module, naming "epoch k" = dr[k]) when a
/// covariance is no longer positive definite. No output is NaN.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "meridian/core/progress.hpp"
#include "meridian/filter/detail/record_store.hpp"
#include "meridian/geodesy/grid.hpp"
#include "meridian/nav/method.hpp"
#include "meridian/nav/observations.hpp"

namespace meridian::nav {

/// Truth points farther apart than this are not interpolated between (s).
inline constexpr double kTruthMaxGap_s = 10.0;
/// A LOP whose station lies closer than this to the ship is not used (m): its direction is
/// undefined there.
inline constexpr double kMinStationDistance_m = 1.0;

/// Most bins of the per-minute error statistics (Options::statistics_bin_s over the line): a
/// smaller bin is an InputError, not an allocation that cannot succeed.
inline constexpr double kMaxStatisticsBins = 100000.0;

// Self-checks of every method (spec §6a; docs/navigation.md, "Self-checks").
/// Window of the LOP checks (s): windows of this length, every half of it.
inline constexpr double kConsistencyWindow_s = 300.0;
/// Fewest LOPs a window needs for the LOP checks.
inline constexpr std::size_t kConsistencyMinLops = 30;
/// A window whose share of rejected LOPs exceeds this is a divergence alarm.
inline constexpr double kMaxRejectedShare = 0.5;
/// A window whose robust innovation spread median|w|/0.6745 exceeds this is inconsistent.
inline constexpr double kMaxInnovationRatio = 2.0;
/// This many consecutive outlying fixes are a divergence alarm.
inline constexpr std::size_t kFixRunAlarm = 2;

/// How the sequential methods reject a gross LOP error (spec §4.4).
enum class Rejection {
  Threshold,  ///< "threshold": |misclosure against the predicted position| > threshold_m
  WTest,      ///< "w-test": |ν|/√S > the two-sided normal critical value at α
};

/// Model of the velocity bias in the EKF (spec §6).
enum class BiasModel {
  RandomWalk,   ///< "random-walk": Ẇ = w, w white with density bias_random_walk (m/s/√s)²
  GaussMarkov,  ///< "gauss-markov": first order, correlation time bias_correlation_time_s,
                ///< stationary σ bias_sigma_m_s
};

struct Options {
  Rejection rejection = Rejection::Threshold;
  double threshold_m = 100.0;   ///< spec §4.4 default; > 0
  double alpha = 0.001;         ///< w-test significance and the EKF's χ² gate; 0 < α < 1
  double segment_s = 60.0;      ///< method II segment length (s), > 0
  /// Methods I and II: W_i = (X̂_i − X_i⁰)/t_i enters the running mean only once t_i ≥ this
  /// (s, ≥ 0; method II: t_i counted from the segment start, and at most half a segment),
  /// because the first W_i divide the position noise by a few seconds.
  double bias_start_s = 180.0;
  double backward_window_s = 60.0;  ///< §4.2 window P₁…P₂ (s), ≥ 0
  /// §5: a fix farther than this from the forward solution at its epoch is flagged and not
  /// combined (m), > 0. Also a fix failing the χ²(2) test at α is flagged.
  double fix_tolerance_m = 200.0;
  double max_reduction_s = 10.0;  ///< farthest an observation may be reduced (s), ≥ 0
  double max_dr_gap_s = 60.0;     ///< a longer DR gap is an InputError (s), > 0
  /// The sequential methods carry the position without a bias state, so the σ of the DR
  /// velocity they use must cover the systematic DR error they do not model: each velocity
  /// component gets this σ (m/s, white per sample, ≥ 0) on top of DrSample::covariance.
  /// The EKF and dead reckoning use DrSample::covariance alone.
  double sequential_sigma_velocity_m_s = 0.4;
  // EKF bias model.
  BiasModel bias_model = BiasModel::RandomWalk;
  double bias_sigma_m_s = 1.0;             ///< prior σ of each bias component (m/s), > 0
  double bias_random_walk_m_s_per_sqrt_s = 0.005;  ///< random-walk density (m/s/√s), ≥ 0
  double bias_correlation_time_s = 600.0;  ///< Gauss–Markov τ (s), > 0
  /// Length of the per-minute statistics bins (s): bin j holds the epochs with
  /// j·bin ≤ t − t₀ < (j+1)·bin; > 0 and at most kMaxStatisticsBins bins over the line.
  double statistics_bin_s = 60.0;
  /// A stretch longer than this without any used observation gets a warning (s), > 0.
  double warn_gap_s = 300.0;
  filter::StorageOptions storage;  ///< where the RTS smoother's records spill
};

/// Initial position at the first DR epoch: the start of dead reckoning and the prior of the
/// sequential methods and the EKF (unless Input::initial_fix gives it).
struct InitialPosition {
  double x_north_m = 0.0;
  double y_east_m = 0.0;
  double sigma_m = 100.0;  ///< σ of each coordinate (m), > 0
};

struct Input {
  std::vector<DrSample> dr;  ///< at least 2, strictly increasing time_s
  std::vector<Station> stations;
  std::vector<Chain> chains;
  std::vector<Lop> lops;     ///< any time order
  std::vector<Fix> fixes;    ///< any time order
  std::vector<TruthPoint> truth;  ///< empty, or strictly increasing times (interpolated)
  InitialPosition initial;
  /// When set, the initial position is this fix (index into `fixes`) moved by the dead
  /// reckoning to the first epoch, and `initial` is not used: x₀ = x_fix − D, D the DR
  /// displacement from t₀ to the fix's time (the first sample's velocity before t₀, as in the
  /// reduction of an observation), covariance the fix's plus that of D (each method's own DR
  /// model: the samples' white noise for dead reckoning and the EKF — whose prior also holds
  /// the bias's share −(t_fix − t₀)·W —, with sequential_sigma_velocity_m_s for the
  /// sequential methods). The fix is then not used again as an observation (it is listed in
  /// Result::skipped): its information is in the prior. The fix must lie within
  /// max_reduction_s before t₀ or after the last epoch, like any observation.
  std::optional<std::size_t> initial_fix;
  Options options;
};

/// Flags of a track point (bits).
enum TrackFlag : unsigned {
  kUsedLop = 1u << 0,       ///< at least one LOP was used at this epoch
  kRejectedLop = 1u << 1,   ///< at least one LOP was rejected at this epoch
  kUsedFix = 1u << 2,       ///< a fix was combined at this epoch
  kFlaggedFix = 1u << 3,    ///< a fix was flagged for inspection and not combined
};

/// A position of one method at one epoch.
struct TrackPoint {
  double time_s = 0.0;
  double x_north_m = 0.0;
  double y_east_m = 0.0;
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();  ///< of (x, y) (m²)
  double bias_north_m_s = 0.0;  ///< the velocity-bias estimate in use (0 without one)
  double bias_east_m_s = 0.0;
  double sigma_bias_north_m_s = 0.0;  ///< 0 where the method gives no σ (methods I, II)
  double sigma_bias_east_m_s = 0.0;
  unsigned flags = 0;  ///< TrackFlag bits
  double sigma_x_m() const;
  double sigma_y_m() const;
};

/// Errors against truth (epochs where truth is available).
struct ErrorStatistics {
  std::size_t epochs = 0;    ///< epochs compared
  double bin_s = 60.0;       ///< length of the per_minute_rms_m bins (Options::statistics_bin_s)
  double rms_m = 0.0;        ///< √mean(|Δ|²), Δ = estimated − true horizontal position
  double max_error_m = 0.0;  ///< max |Δ|
  /// Per bin of Options::statistics_bin_s from the first epoch; a bin without truth is NaN
  /// in memory and null in JSON.
  std::vector<double> per_minute_rms_m;
  double mean_nees = 0.0;    ///< mean of Δᵀ·P⁻¹·Δ (2 degrees of freedom)
};

/// A time-invariant parameter of a chain (spec §4.3) as estimated by one method.
struct ChainParameter {
  std::size_t chain = 0;
  std::string chain_name;  ///< Chain::name
  std::string name;      ///< "scale" or "offset_m"
  double value = 0.0;    ///< dimensionless or m
  double sigma = 0.0;
};

/// The verdict of a method's self-checks (spec §6a; docs/navigation.md, "Self-checks"): from
/// the data alone, never from truth.
enum class MethodStatus {
  Consistent,    ///< "consistent": every check passed; its σ are as valid as its model
  Inconsistent,  ///< "inconsistent": its residuals are wider than its σ say
  Diverged,      ///< "diverged": it lost the observations (a run of outlying fixes, most LOPs rejected)
};
/// "consistent", "inconsistent", "diverged".
std::string to_string(MethodStatus s);

/// One failed self-check over a stretch of the line.
struct ConsistencyAlarm {
  MethodStatus status = MethodStatus::Inconsistent;
  /// "fix-run" (consecutive fixes outside their χ²(2) limit or fix_tolerance_m),
  /// "rejected-share" (most LOPs of a window rejected), "innovation-spread" (the LOP innovations
  /// of a window wider than their σ), "fix-spread" (the fix misclosures of the line wider than
  /// their σ)
  std::string check;
  double from_s = 0.0;  ///< the stretch concerned (times of its first and last epoch)
  double to_s = 0.0;
  std::size_t from_epoch = 0;
  std::size_t to_epoch = 0;
  std::string reason;  ///< what was measured against which limit
};

/// A method's self-checks: the statistics and the alarms they raised.
struct Consistency {
  MethodStatus status = MethodStatus::Consistent;  ///< the worst alarm's
  std::vector<ConsistencyAlarm> alarms;
  std::size_t fixes_tested = 0;     ///< fixes compared with the method's position
  std::size_t fixes_outlying = 0;   ///< of them outside χ²_{1−α}(2) or fix_tolerance_m
  std::size_t longest_fix_run = 0;  ///< most consecutive outlying fixes
  /// √(mean χ²/2) of the fix misclosures, each normalised by the combined σ (fix + method):
  /// ≈ 1 when the σ are right; NaN without fixes
  double fix_sigma_ratio = 0.0;
  std::size_t lops_tested = 0;    ///< LOP innovations monitored (forward methods; 0 otherwise)
  std::size_t lops_rejected = 0;
  double max_rejected_share = 0.0;  ///< the largest share of rejected LOPs in a window
  /// The largest robust spread of the normalised LOP innovations in a window, median|w|/0.6745
  /// (≈ 1 when the σ are right); NaN when not monitored
  double max_innovation_ratio = 0.0;
  /// The σ of the method stand for its errors only when it is consistent.
  bool sigma_valid() const { return status == MethodStatus::Consistent; }
};

struct MethodResult {
  Method method = Method::DeadReckoning;
  std::vector<TrackPoint> track;  ///< one per epoch
  std::vector<ChainParameter> parameters;  ///< at the last epoch (smoother: the whole line)
  std::optional<ErrorStatistics> errors;   ///< with truth
  Consistency consistency{};  ///< the self-checks (no truth used)
};

/// An observation that a method did not use.
struct RejectedObservation {
  enum class Kind { Lop, Fix };
  Kind kind = Kind::Lop;
  std::size_t index = 0;   ///< into Input::lops or Input::fixes
  Method method = Method::SequentialNoBias;
  double time_s = 0.0;
  /// observed − computed against the predicted position (m); for a fix its distance from it
  double misclosure_m = 0.0;
  double statistic = 0.0;     ///< |w| for a LOP (w-test), √(χ²) for a fix (0 for the threshold)
  std::string reason;         ///< "|misclosure| 153.2 m > 100 m", "|w| = 4.10 > 3.29", …
  /// Where the observation came from ("lops.csv:14"): filled by process(SurveyLine) from the
  /// records' sources, empty from process(Input).
  std::string source;
};

/// An observation no method could use (more than max_reduction_s from every epoch), or the fix
/// that gave the initial position (Input::initial_fix).
struct SkippedObservation {
  RejectedObservation::Kind kind = RejectedObservation::Kind::Lop;
  std::size_t index = 0;
  double time_s = 0.0;
  std::string reason;
  std::string source;  ///< as RejectedObservation::source
};

struct Result {
  std::vector<MethodResult> methods;  ///< in kAllMethods order; FixClosure only with fixes
  std::vector<RejectedObservation> rejected;
  std::vector<SkippedObservation> skipped;
  std::size_t epochs = 0;
  std::size_t lops_used = 0;   ///< LOPs reduced to an epoch (before rejection)
  std::size_t fixes_used = 0;
  std::vector<std::string> notes;     ///< assumptions and defaults
  std::vector<std::string> warnings;  ///< gaps without observations, flagged fixes, …
  /// The projection of the plane (x north, y east) when the line has one (set by
  /// process(SurveyLine), survey_line.hpp): writers give latitudes and longitudes with it
  /// (geodesy::TransverseMercatorGrid::reverse). Absent: plane coordinates only.
  std::optional<geodesy::GridDefinition> projection;
  /// The result of `m`; nullptr when not computed.
  const MethodResult* find(Method m) const;
};

/// Throws InputError (field "options.<name>") unless every option is in range.
void validate(const Options& options);
/// Run every method over the line (file comment).
Result process(const Input& input, Progress* progress = nullptr);

}  // namespace meridian::nav
