#pragma once
/// \file azimuth_chain.hpp
/// From N_G to a grid azimuth (spec §6), with σ propagated at each step.
///
///   A_G = r − N_G                 gyro azimuth
///   A   = A_G + E                 astronomic azimuth
///   α   = A − η·tan φ − (ξ·sin α − η·cos α)·cot z
///                                 geodetic azimuth (Laplace), when η is known;
///                                 the second term when ξ and z are known too
///   T   = α − γ (+ δ)             grid azimuth of the chord (δ when the target is known)
///
/// Angles in radians; azimuths clockwise from north, normalised to [0, 2π).
/// Errors of A_G, E, ξ and η are independent; z, γ and δ are exact. The steps from
/// A on are geodesy::azimuth_from_astronomic (geodesy/azimuth_chain.hpp:
/// formulas, signs, errors); this layer adds the gyro step A = A_G + E,
/// σ_A = hypot(σ_AG, σ_E), and the notes on steps not applied.

#include <optional>
#include <string>
#include <vector>

#include "meridian/gyro/instrument.hpp"

namespace meridian::gyro {

struct AzimuthChainInput {
  /// A_G = r − N_G with σ (from the pointing and N_G), e.g. the mean of
  /// several determinations (see gyro_azimuth() in determination.hpp).
  Uncertain gyro_azimuth_rad;
  Uncertain instrument_constant_rad;      ///< E (signed) with σ
  double latitude_rad = 0.0;              ///< geodetic latitude φ of the station
  std::optional<Uncertain> eta_rad;       ///< η, prime-vertical deflection (astro − geodetic)
  double convergence_rad = 0.0;           ///< γ at the station (grid north from true north, clockwise)
  std::optional<double> arc_to_chord_rad; ///< δ for the target line
  /// ξ, meridian deflection (astro − geodetic); needs η. Used with zenith_distance_rad.
  std::optional<Uncertain> xi_rad;
  /// Zenith distance z of the sight to the target (radians, 10°…170°); none:
  /// horizontal, the zenith-distance term omitted.
  std::optional<double> zenith_distance_rad;
};

struct AzimuthChainResult {
  Uncertain gyro_azimuth_rad;       ///< A_G
  Uncertain astronomic_azimuth_rad; ///< A
  Uncertain geodetic_azimuth_rad;   ///< α (= A when η is unknown, see notes)
  Uncertain grid_azimuth_rad;       ///< T
  double laplace_correction_rad = 0.0;  ///< −η·tan φ (0 when η unknown)
  /// −(ξ·sin α − η·cos α)·cot z (0 when not applied): α = A + laplace + this.
  double zenith_correction_rad = 0.0;
  /// The zenith distance given (radians), whether or not the term was applied.
  std::optional<double> zenith_distance_rad;
  double convergence_rad = 0.0;         ///< γ
  double arc_to_chord_rad = 0.0;        ///< δ (0 when not computed)
  bool laplace_applied = false;
  bool zenith_term_applied = false;  ///< ξ, η and z all known
  bool arc_to_chord_applied = false;
  std::vector<std::string> notes;
};

/// The chain of one line. Throws InputError as geodesy::azimuth_from_astronomic
/// (e.g. |η| > 0.01 rad or |φ| ≥ 90° when η is given, ξ without η, z outside
/// 10°…170°). Notes only on steps not applied because η or δ is missing; the
/// caller says where ξ and z came from.
AzimuthChainResult azimuth_chain(const AzimuthChainInput& in);

}  // namespace meridian::gyro
