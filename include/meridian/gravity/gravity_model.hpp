#pragma once
/// \file gravity_model.hpp
/// A global gravity field model as read from a file: metadata, the
/// gravitational coefficients and the reference (normal) field against
/// which disturbing quantities are formed.

#include <optional>
#include <string>

#include "meridian/gravity/coefficients.hpp"
#include "meridian/gravity/normal_gravity.hpp"

namespace meridian::gravity {

/// Degree/order truncation applied while reading (memory is proportional
/// to what is kept). Negative = keep everything; max_order < 0 with
/// max_degree ≥ 0 means max_order = max_degree.
struct Truncation {
  int max_degree = -1;
  int max_order = -1;
};

/// GeographicLib's optional "correction" set: a harmonic series (evaluated
/// on the unit sphere) added to T/γ0 for geoid heights (zeta-to-N), in
/// metres, times `multiplier`, plus `height_offset_m`.
struct GeoidCorrection {
  SphericalHarmonicCoefficients coefficients;
  double multiplier = 1.0;       ///< GeographicLib CorrectionMultiplier
  double height_offset_m = 0.0;  ///< GeographicLib HeightOffset (ζ0, m)
};

/// A spherical-harmonic gravity model
/// V = GM/r Σ_n (a/r)^n Σ_m P̄_nm(sin ψ)(C̄_nm cos mλ + S̄_nm sin mλ)
/// (ψ geocentric latitude, λ longitude, r geocentric radius). C̄_00 is 1.
struct GravityModelData {
  std::string name;                  ///< model name (ICGEM modelname / egm Name)
  std::string description;
  /// As stated by the file ("tide_free", "zero_tide", "mean_tide", "unknown", …);
  /// empty when the file does not say (a GeographicLib `.egm` never does).
  std::string tide_system;
  /// As stated by the file (ICGEM `norm`: "fully_normalized"; `.egm`
  /// `Normalization`: "FULL"); empty when it does not say. Either way the
  /// coefficients are fully normalised (coefficients.hpp): the readers
  /// reject every other normalisation, and both formats default to it.
  std::string normalization;
  std::string source_file;           ///< path it was read from (empty for generated models)
  double gm_m3_s2 = 0;               ///< GM of the model (m³/s²)
  double radius_m = 0;               ///< reference radius a of the expansion (m)
  int file_max_degree = 0;           ///< degree stated by / present in the file before truncation
  SphericalHarmonicCoefficients coefficients;
  NormalFieldParameters reference = wgs84_normal_field();  ///< normal field removed to form T
  std::optional<GeoidCorrection> correction;               ///< zeta-to-N correction, if any
};

}  // namespace meridian::gravity
