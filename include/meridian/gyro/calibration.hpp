#pragma once
/// \file calibration.hpp
/// Instrument constant E from a line of known azimuth observed before and
/// after the unknown line ("known–unknown–known", spec §5).

#include <optional>
#include <string>
#include <vector>

#include "meridian/gyro/instrument.hpp"

namespace meridian::gyro {

/// Mean of several gyro azimuths (radians) with both σ estimates.
struct AzimuthMean {
  Uncertain mean;                  ///< mean (radians, normalised to [0, 2π)); sigma = the one used
  double sigma_propagated = 0.0;   ///< sqrt(Σσ_i²)/n from the individual σ
  double sigma_empirical = 0.0;    ///< sqrt(Σv²/(n(n−1))), NaN for n = 1
  /// One-run standard deviation (一次测定中误差) m = sqrt(Σv²/(n−1)) of the
  /// values about their mean, NaN for n = 1.
  double one_run_sigma = 0.0;
  double max_difference = 0.0;     ///< largest |a_i − a_j| (radians)
  int count = 0;
};

/// Mean of directions given as circle values (radians); values are unwrapped
/// about the first so 359°59′ and 0°01′ average to 0°. The σ used is the
/// larger of the propagated and (n ≥ 2) empirical σ — the conservative choice
/// surveyors expect when determinations disagree more than their σ says.
AzimuthMean mean_direction(const std::vector<Uncertain>& values_rad);

struct InstrumentConstantResult {
  std::vector<Uncertain> before;        ///< E_i = A_known − A_G,i (radians, signed)
  std::vector<Uncertain> after;
  Uncertain mean;                       ///< E used downstream (σ includes σ(A_known))
  std::optional<double> difference_rad; ///< mean(after) − mean(before) when both given
  double tolerance_rad = 0.0;
  bool within_tolerance = true;
  std::vector<std::string> warnings;
};

/// E from the known line's astronomic azimuth and the gyro azimuths observed
/// on it before and after (radians, with σ). E_i is normalised to [−π, π).
/// The σ of the mean E combines the σ of the mean gyro azimuth (as in
/// mean_direction) with σ(A_known), which is common to all E_i.
/// Throws InputError when no determination is given.
InstrumentConstantResult instrument_constant(Uncertain known_astronomic_azimuth_rad,
                                             const std::vector<Uncertain>& gyro_azimuths_before_rad,
                                             const std::vector<Uncertain>& gyro_azimuths_after_rad,
                                             double tolerance_rad);

}  // namespace meridian::gyro
