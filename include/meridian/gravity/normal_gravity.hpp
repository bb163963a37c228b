#pragma once
/// \file normal_gravity.hpp
/// The normal gravity field of a level ellipsoid (Somigliana–Pizzetti),
/// implemented from the closed forms of Heiskanen & Moritz, Physical Geodesy
/// (1967), §2-7…2-10 and §6-2, valid at any point outside or near the
/// ellipsoid. Used to remove the normal field from a model and to divide by γ.

#include <string>

namespace meridian::gravity {

/// Defining constants of a level ellipsoid. Exactly one of `flattening`
/// and `j2` is used: `flattening` when `j2` is 0, else `j2` (the flattening
/// is then derived, as GRS80 does).
struct NormalFieldParameters {
  std::string name = "WGS84";
  double a_m = 6378137.0;                 ///< equatorial radius (m)
  double gm_m3_s2 = 3986004.418e8;        ///< geocentric gravitational constant GM (m³/s²)
  double omega_rad_s = 7292115e-11;       ///< angular velocity (rad/s)
  double flattening = 1 / 298.257223563;  ///< geometric flattening f (used when j2 == 0)
  double j2 = 0.0;                        ///< dynamical form factor J2 (dimensionless), 0 = derive from f
};

NormalFieldParameters wgs84_normal_field();  ///< a, GM, ω, f of WGS84
NormalFieldParameters grs80_normal_field();  ///< a, GM, ω, J2 = 108263e-8 of GRS80

/// Geocentric Cartesian position (Earth-centred, Earth-fixed), metres.
struct EcefPosition {
  double x_m = 0, y_m = 0, z_m = 0;
};

/// The normal (reference) gravity field: gravitational plus centrifugal
/// potential U of the level ellipsoid. Immutable.
class NormalGravity {
 public:
  /// Throws InputError when a, GM or f/J2 are not positive and finite, or
  /// ω is negative or not finite.
  explicit NormalGravity(const NormalFieldParameters& p);

  double a_m() const noexcept { return a_; }
  double b_m() const noexcept { return b_; }
  double gm_m3_s2() const noexcept { return gm_; }
  double omega_rad_s() const noexcept { return omega_; }
  double flattening() const noexcept { return f_; }
  double e2() const noexcept { return e2_; }  ///< first eccentricity squared
  /// J2 (derived from f, or as given).
  double j2() const noexcept { return j2_; }
  /// Zonal coefficient J_n of the normal gravitational potential
  /// (unnormalised, V = GM/r [1 − Σ J_n (a/r)^n P_n(sin ψ)]; H&M eq. 2-92):
  /// J_0 = −1, J_n = 0 for odd n.
  double jn(int n) const noexcept;
  /// Normal gravity at the equator / pole on the ellipsoid (m/s²).
  double gamma_equator_m_s2() const noexcept { return gamma_e_; }
  double gamma_pole_m_s2() const noexcept { return gamma_p_; }
  /// Normal gravity on the ellipsoid surface at geodetic latitude
  /// `lat_rad` ∈ [−π/2, π/2] (Somigliana's closed formula, m/s²).
  double surface_gravity_m_s2(double lat_rad) const noexcept;
  /// Normal gravity vector ∇U (gravitation + centrifugal) at an ECEF point
  /// (m/s², ECEF components; points roughly towards the centre).
  EcefPosition gravity_vector_m_s2(const EcefPosition& p) const noexcept;
  /// |∇U| at an ECEF point (m/s²).
  double gravity_magnitude_m_s2(const EcefPosition& p) const noexcept;
  /// Geodetic (lat_rad, lon_rad, height_m above this ellipsoid) to ECEF.
  EcefPosition to_ecef(double lat_rad, double lon_rad, double height_m) const noexcept;

 private:
  double a_, gm_, omega_, f_, j2_, b_, e2_, ep2_, E_, q0_, gamma_e_, gamma_p_, k_;
};

}  // namespace meridian::gravity
