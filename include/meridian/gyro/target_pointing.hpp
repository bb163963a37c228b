#pragma once
/// \file target_pointing.hpp
/// The circle reading to the target of a gyro run from theodolite rounds
/// (测回): each round points the target face left (盘左) and face right
/// (盘右), booked before and after the run. A round's direction is the mean
/// of the two faces, L and R − 180°; their difference 2C = L − (R − 180°)
/// is twice the collimation error, shown so a checker sees the pointing
/// quality. The run's target reading is the mean of its rounds.

#include <vector>

#include "meridian/core/uncertain.hpp"
#include "meridian/core/units.hpp"

namespace meridian::gyro {

/// One round: the target pointed face left and face right (circle readings,
/// radians).
struct TargetRound {
  enum class When { Before, After };
  When when = When::Before;            ///< before or after the gyro run
  double face_left_rad = 0.0;
  double face_right_rad = 0.0;
};

/// The rounds reduced.
struct TargetDirection {
  /// Mean direction of the rounds in [0, 2π); σ = the larger of the stated
  /// pointing σ/sqrt(n) and the empirical σ of the mean (n ≥ 2).
  Uncertain reading_rad;
  std::vector<double> round_rad;       ///< (L + R − 180°)/2 of each round, in [0, 2π)
  std::vector<double> two_c_rad;       ///< 2C = L − (R − 180°) of each round, in [−π, π)
  double spread_rad = 0.0;             ///< largest difference between the rounds
};

/// Reduce the rounds (at least one). `sigma_pointing_rad` is the σ of one
/// round's direction (≥ 0). Throws InputError when a face-right reading is
/// not about 180° from the face-left one (|2C| > 1°: a face booked wrong),
/// naming the round ("target_rounds[1]").
TargetDirection reduce_target_rounds(const std::vector<TargetRound>& rounds, double sigma_pointing_rad);

/// Whether the rounds of one run agree, by Meridian's plausibility limits: the round directions
/// within max(10″, 3·√2·σ of a round) and 2C within kTwoCVariationLimit_rad (a face reading
/// booked wrong moves the mean by half its error). Radians.
struct RoundsAgreement {
  double spread_limit_rad = 0.0;   ///< max(10″, 3·√2·sigma_round_rad)
  double two_c_variation_rad = 0.0;  ///< max − min of the rounds' 2C
  bool agree = true;               ///< spread ≤ its limit and 2C variation ≤ 20″
};
inline constexpr double kTwoCVariationLimit_rad = 20.0 * units::kArcsecond;  ///< 20″
/// The agreement of `t`'s rounds (at least two; one round always agrees).
RoundsAgreement rounds_agreement(const TargetDirection& t, double sigma_round_rad);

}  // namespace meridian::gyro
