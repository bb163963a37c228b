#pragma once
/// \file frames.hpp
/// The Earth-fixed and local frames Meridian uses, stated once, and the sign
/// convention of the deflection of the vertical. Gravity, navigation and the
/// deflection-of-the-vertical workflows refer here instead of restating it.
///
/// Frames (all right-handed, axes in this order):
/// * **ECEF** (X, Y, Z): Earth-centred, Earth-fixed, WGS84-style: origin at
///   the centre of the ellipsoid, Z along the rotation (minor) axis to the
///   north, X in the plane of the zero meridian, Y = Z × X (90° E).
/// * **ENU** (e, n, u) at geodetic latitude φ and longitude λ: the local
///   geodetic frame. u is the outward **ellipsoid normal** (the geodetic
///   zenith), n points to the north along the meridian (horizontal, i.e.
///   perpendicular to u), e = n × u points east. In ECEF:
///     e = (−sin λ, cos λ, 0)
///     n = (−sin φ cos λ, −sin φ sin λ, cos φ)
///     u = ( cos φ cos λ,  cos φ sin λ, sin φ)
///   The rotation R_ecef→enu has e, n, u as its rows: v_enu = R·v_ecef.
///   This is GeographicLib::LocalCartesian's frame (its x, y, z) and the
///   transpose of the matrix GeographicLib::Geocentric::Forward returns.
/// * **NED** (n, e, d) at (φ, λ): the same axes reordered, d = −u (the
///   navigation convention, e.g. for attitude matrices): v_ned = P·v_enu with
///   P = [[0,1,0],[1,0,0],[0,0,−1]], P = Pᵀ = P⁻¹.
/// * **Geocentric local frame** (e, n_ψ, r) at geocentric latitude ψ and
///   longitude λ: up r is the **radial** direction (from the Earth's centre
///   through the point), n_ψ is north perpendicular to it in the meridian
///   plane, e is the same east as in ENU. It is the ENU formula above with φ
///   replaced by ψ. Spherical-harmonic gravity derivatives (∂/∂ψ, ∂/∂r) live
///   in this frame (gravity/gravity_field.hpp).
///
/// The geodetic and geocentric local frames differ by a rotation about the
/// common east axis through φ − ψ, the angle between the ellipsoid normal and
/// the radius (0 at the equator and the poles, largest ≈ 11.5′ near 45° on
/// the ellipsoid; φ > ψ in the north). For a point at height h on an
/// ellipsoid (a, f, e² = f(2 − f)), N = a/√(1 − e² sin²φ):
///     tan ψ = (N(1 − e²) + h)·sin φ / ((N + h)·cos φ).
///
/// Deflection of the vertical (spec README): the astronomic latitude and
/// longitude Φ, Λ give the direction of the plumb line (the astronomic zenith,
/// upwards along gravity's negative); the geodetic φ, λ give the ellipsoid
/// normal (the geodetic zenith). Astronomic minus geodetic:
///     ξ = Φ − φ                (north–south, meridian component)
///     η = (Λ − λ)·cos φ        (east–west, prime-vertical component)
/// ξ > 0: the astronomic zenith lies north of the geodetic one (the plumb bob
/// hangs to the south of the normal); η > 0: the astronomic zenith lies east
/// of it. To first order the astronomic zenith in the geodetic ENU frame is
///     (e, n, u) ≈ (η, ξ, 1) normalised,
/// and the tilt is θ = √(ξ² + η²). Sources: Hofmann-Wellenhof & Moritz,
/// Physical Geodesy, 2nd ed. (2006) §2.19 (deflection, Laplace) and §5.13
/// (local frames); Torge & Müller, Geodesy, 4th ed. (2012) §3.2–3.3;
/// GeographicLib, LocalCartesian and Geocentric documentation.
///
/// Units: angles in radians, heights in metres. Latitudes north positive in
/// [−π/2, π/2]; longitudes east positive, any value. Errors: InputError for
/// non-finite input, |latitude| > π/2, or the range limits stated per
/// function.

#include <Eigen/Core>

#include "meridian/geodesy/ellipsoid.hpp"

namespace meridian::geodesy {

/// Largest accepted deflection component |ξ|, |η| (radians) where a function
/// takes a deflection: 0.01 rad ≈ 34′, far above the largest deflections on
/// Earth (about 1′); larger values are almost surely a unit error. The same
/// bound guards laplace_correction_rad.
inline constexpr double kMaxDeflection_rad = 0.01;

/// Rotation ECEF → geodetic ENU at (lat_rad, lon_rad): v_enu = R·v_ecef, rows
/// e, n, u (see the file comment). Throws InputError for non-finite input or
/// |lat_rad| > π/2. At a pole the frame is the limit along the meridian λ.
Eigen::Matrix3d rotation_ecef_to_enu(double lat_rad, double lon_rad);

/// Rotation ECEF → geodetic NED at (lat_rad, lon_rad): v_ned = R·v_ecef, rows
/// n, e, −u. Throws as rotation_ecef_to_enu.
Eigen::Matrix3d rotation_ecef_to_ned(double lat_rad, double lon_rad);

/// The axis permutation ENU → NED (v_ned = P·v_enu); P is its own inverse
/// and transpose, so it also maps NED → ENU.
Eigen::Matrix3d rotation_enu_to_ned();
/// NED → ENU; the same matrix as rotation_enu_to_ned().
Eigen::Matrix3d rotation_ned_to_enu();

/// Geocentric latitude ψ (radians, same sign as φ, |ψ| ≤ π/2) of the point at
/// geodetic latitude lat_rad and ellipsoidal height height_m on ellipsoid e
/// (formula in the file comment; ψ = φ at the equator and the poles). Throws
/// InputError for non-finite input, |lat_rad| > π/2, an invalid ellipsoid
/// (a ≤ 0, f outside [0, 1)) or h ≤ −N(1 − e²) (≈ −6335 km at the equator),
/// where the point would reach the Earth's centre.
double geocentric_latitude_rad(double lat_rad, double height_m, const Ellipsoid& e);

/// Rotation from the geocentric local frame (e, n_ψ, r) at geocentric
/// latitude geocentric_lat_rad to the geodetic ENU frame at geodetic latitude
/// lat_rad (same meridian): v_enu = R·v_geocentric with, for d = φ − ψ,
///     R = [[1, 0, 0], [0, cos d, −sin d], [0, sin d, cos d]],
/// i.e. the radial direction (0, 0, 1) is (0, −sin d, cos d) in ENU: south
/// of the normal in the northern hemisphere. Equals
/// rotation_ecef_to_enu(φ, λ)·rotation_ecef_to_enu(ψ, λ)ᵀ for any λ. Throws
/// InputError for non-finite input or |latitude| > π/2.
Eigen::Matrix3d rotation_geocentric_to_enu(double lat_rad, double geocentric_lat_rad);

/// The deflection of the vertical, astronomic minus geodetic (file comment).
struct Deflection {
  double xi_rad = 0.0;  ///< ξ = Φ − φ, north–south; > 0: astronomic zenith north of the normal
  double eta_rad = 0.0;  ///< η = (Λ − λ)·cos φ, east–west; > 0: astronomic zenith east of it
};

/// ξ, η from astronomic (Φ, Λ) and geodetic (φ, λ) coordinates (radians), by
/// the definition: ξ = Φ − φ, η = (Λ − λ)·cos φ with Λ − λ reduced to
/// [−π, π). Exact; no size limit. Throws InputError for non-finite input or a
/// latitude beyond ±π/2.
Deflection deflection_from_astronomic(double astro_lat_rad, double astro_lon_rad, double lat_rad,
                                      double lon_rad);

/// The astronomic zenith (unit vector along the plumb line, upwards) in the
/// geodetic ENU frame at (lat_rad, lon_rad), **exact**: the ENU "up" of
/// (astro_lat_rad, astro_lon_rad) rotated into the ENU frame of
/// (lat_rad, lon_rad). No size limit. Throws InputError for non-finite input
/// or a latitude beyond ±π/2.
Eigen::Vector3d astronomic_zenith_enu(double astro_lat_rad, double astro_lon_rad, double lat_rad,
                                      double lon_rad);

/// The astronomic zenith in the geodetic ENU frame at latitude lat_rad from
/// (ξ, η), **exact**: Φ = φ + ξ, Λ − λ = η / cos φ, then as above (λ drops
/// out). Differs from the first-order vector by O(θ²), θ = √(ξ² + η²): the
/// east component by −ξ·η·tan φ, the north one by (η²/2)·tan φ, e.g.
/// 8.5e-8 rad (0.018″) for ξ = η = 1′ at 45°.
/// Throws InputError for non-finite input, |ξ| or |η| > kMaxDeflection_rad,
/// |lat_rad| ≥ π/2 (η/cos φ undefined at a pole) or |φ + ξ| > π/2.
Eigen::Vector3d astronomic_zenith_enu(const Deflection& d, double lat_rad);

/// The astronomic zenith in the geodetic ENU frame to **first order** in ξ,
/// η: (η, ξ, 1)/√(1 + ξ² + η²), independent of φ. Throws InputError for
/// non-finite input or |ξ| or |η| > kMaxDeflection_rad.
Eigen::Vector3d astronomic_zenith_enu_first_order(const Deflection& d);

/// Exact inverse of astronomic_zenith_enu(Deflection, φ): ξ, η of the
/// direction zenith_enu (any length > 0; normalised here) given in the
/// geodetic ENU frame at latitude lat_rad, by Φ = atan2(Z, √(X² + Y²)) and
/// Λ − λ = atan2(Y, X) of the same direction in a frame rotated to λ = 0,
/// then ξ = Φ − φ, η = (Λ − λ)·cos φ (η = 0 at a pole). No size limit on the
/// result. Throws InputError for a non-finite or zero vector or a latitude
/// that is non-finite or beyond ±π/2.
Deflection deflection_from_zenith_enu(const Eigen::Vector3d& zenith_enu, double lat_rad);

/// Inverse of astronomic_zenith_enu_first_order: ξ = n/u, η = e/u (exact
/// inverse of that function, first order as a deflection). Throws InputError
/// for a non-finite vector or u ≤ 0 (a direction at or below the horizon).
Deflection deflection_from_zenith_enu_first_order(const Eigen::Vector3d& zenith_enu);

}  // namespace meridian::geodesy
