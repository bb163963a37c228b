#pragma once
/// \file determination.hpp
/// One gyro determination, whatever its mode and method: observations in,
/// N_G with σ (and every intermediate quantity) out. This is what
/// `meridian gyro reduce` runs for each entry of a file.

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "meridian/gyro/instrument.hpp"
#include "meridian/gyro/nontracking.hpp"
#include "meridian/gyro/reversal.hpp"
#include "meridian/gyro/stochastic_choice.hpp"
#include "meridian/gyro/target_pointing.hpp"
#include "meridian/gyro/tracking.hpp"
#include "meridian/gyro/unified_fit.hpp"
#include "meridian/gyro/zero_position.hpp"

namespace meridian::gyro {

enum class Mode { Tracking, NonTracking };
std::string to_string(Mode m);  ///< "tracking", "non-tracking"

/// A reduction method of either mode: non-tracking (transit,
/// time-difference, direct, timed-amplitude-1/-2, lsq) or tracking
/// (two-point, schuler, lsq-linear, lsq).
using Method = std::variant<NonTrackingMethod, ReversalMethod>;

/// The method's name as written in files and reports.
std::string to_string(const Method& m);

/// The method of `mode` called `name`; "all" is not a method (see
/// DeterminationInput::method). Throws InputError listing the names accepted
/// for that mode.
Method method_from_string(Mode mode, const std::string& name);

/// A requested method's name: "all" when every applicable method is run.
std::string method_request_name(const std::optional<Method>& requested);

/// A determination as read from a field book.
struct DeterminationInput {
  std::string label;                 ///< free text, e.g. "D1 (known line, before)"
  Mode mode = Mode::NonTracking;
  /// The method to run (of this determination's mode); none: every
  /// applicable method ("all" in files), reporting the recommended one.
  std::optional<Method> method;
  double clamp_reading_rad = 0.0;    ///< N′ (non-tracking only)
  NonTrackingObservations nontracking;
  TrackingObservations tracking;
  /// α_p given directly (div, σ); used unless runs are given.
  ZeroPosition zero_position;
  std::optional<ZeroPositionRun> zero_before;  ///< motor-off run before the gyro run
  std::optional<ZeroPositionRun> zero_after;   ///< and after
  /// Circle reading to the target of this determination (radians, σ of the
  /// pointing), or the rounds it was reduced from (target_rounds), or both
  /// (they must then agree within 0.5″).
  std::optional<Uncertain> target_reading_rad;
  std::vector<TargetRound> target_rounds;
  double target_round_sigma_rad = 0.0;  ///< σ of one round's direction (≥ 0)
  // The record sheet (shown in reports, not used in the arithmetic).
  std::string time;       ///< clock time of the run as booked, e.g. "08:40"
  std::string observer;   ///< when not the campaign's observer
  /// The stochastic model of this determination's reversal readings (campaign files only;
  /// overrides CampaignInput::stochastic_model, and an error when it cannot be used: see
  /// stochastic_determination.hpp). None: the campaign's.
  std::optional<StochasticChoice> stochastic_model;
};

/// Options that apply to all determinations.
struct ReduceOptions {
  ReversalMethod zero_position_method = ReversalMethod::Schuler;
  double zero_position_tolerance_div = kDefaultZeroPositionTolerance_div;
  UnifiedFitOptions unified_fit;
};

/// The outcome of one method.
struct MethodResult {
  Method method;                            ///< the method that gave this result
  NorthReading north;                       ///< N_G, σ, ΔN, zero-position correction
  /// Non-tracking: the method's approximation error carried to N_G,
  /// (1+λ)·τ·(β_method − β_exact) in radians; 0 for exact methods.
  double approximation_error_rad = 0.0;
  std::optional<BetaResult> beta;           ///< non-tracking simple methods and lsq
  std::optional<UnifiedFitResult> fit;      ///< non-tracking lsq
  std::optional<ReversalResult> reversal;   ///< tracking
};

struct DeterminationResult {
  std::string label;
  Mode mode = Mode::NonTracking;
  std::optional<Method> method;             ///< as requested (none: all)
  /// The result reported for the determination: the requested method, or
  /// with all methods the recommended one (non-tracking: lsq when it can be run,
  /// else direct, timed-amplitude, transit, time-difference in that order;
  /// tracking: lsq, else lsq-linear, schuler, two-point).
  MethodResult primary;
  std::vector<MethodResult> all;            ///< every applicable method, when all were requested
  ZeroPosition zero_position_used;          ///< α_p applied (if any)
  std::optional<TargetDirection> target;    ///< the target rounds reduced, when given
  std::optional<ZeroPositionSummary> zero_position;  ///< from before/after runs
  /// The stochastic model of the reversal readings behind primary.north (white unless a
  /// campaign asked for another: with_stochastic_model).
  StochasticUse stochastic;
  std::vector<std::string> warnings;
};

/// Reduce one determination. Errors carry the field path inside the
/// determination (e.g. "crossings[1].times_s"); callers add the file and
/// the determination index.
DeterminationResult reduce_determination(const DeterminationInput& in, const Instrument& inst,
                                         const ReduceOptions& options = {});

/// Gyro azimuth A_G = r − N_G of a determination that has a target reading
/// or rounds (radians, σ combining pointing and N_G). Throws InputError
/// otherwise.
Uncertain gyro_azimuth(const DeterminationResult& r, const DeterminationInput& in);

/// Whether two runs hold the same gyro observations (the same mode; for tracking the same
/// reversal readings, for motor-off the same crossing levels and times and reversal readings),
/// exactly as booked: a run booked twice, or the same run in two orientations. Target and
/// zero-position readings are not compared (a copied run with one face reading retyped is still a copy).
bool same_observations(const DeterminationInput& a, const DeterminationInput& b);

}  // namespace meridian::gyro
