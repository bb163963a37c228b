#pragma once
/// \file attitude_difference.hpp
/// The observation of the dynamic deflection-of-the-vertical method (shared/spec/deflection.md
/// §2): the rotation between the gyro-only LGU/GNSS attitude and the accelerometer-levelled
/// INS/GNSS attitude, and the three small angles ΔΦ = (ΔΦ_E, ΔΦ_N, ΔΦ_U) extracted from it.
///
/// Frames (geodesy/frames.hpp): n is the geodetic ENU frame (e, n, u; u the ellipsoid normal);
/// n′ is the frame the INS/GNSS levels to (its up axis along the plumb line); b is the body
/// frame. An attitude matrix C_b^n maps body coordinates to n coordinates, v_n = C_b^n·v_b, and
/// is a proper rotation (CᵀC = I, det C = +1). The axes of n and n′ are in the order E, N, U.
///
///   C = C_{n′}^{n} = C_b^n · (C_b^{n′})ᵀ      (the LGU/GNSS matrix times the INS/GNSS transpose)
///
/// ΔΦ is defined by C = exp(−[ΔΦ×]) ≈ I − [ΔΦ×], with [a×] the cross-product matrix
/// [[0, −a₃, a₂], [a₃, 0, −a₁], [−a₂, a₁, 0]]. This is the psi-angle convention of the spec:
/// a computed attitude (I − [φ×])·C_true carries the error angles φ, so with the LGU errors φ,
/// the INS/GNSS errors v and the tilt D of n′ the difference is ΔΦ = φ − v + D to first order,
/// and D = (ξ, −η, 0) for the deflection (ξ, η) of geodesy/frames.hpp (the up axis of n′, the
/// third column of C, is ≈ (η, ξ, 1) = (−ΔΦ_N, ΔΦ_E, 1)). Hence spec §4:
/// ΔΦ_E = φ_E − v_E + ξ, ΔΦ_N = φ_N − v_N − η.
///
/// Two extractions, which differ by at most |ΔΦ|²/2 (the symmetric part ½[ΔΦ×]² of C):
/// 1.2e-9 rad (2.4e-4″) at |ΔΦ| = 10″, 0.009″ at 60″ (tested):
/// * skew-symmetric part, the spec's small-angle form with 1-based indices
///   ΔΦ_E = C(2,3), ΔΦ_N = C(3,1), ΔΦ_U = C(1,2) (one element each, as published);
/// * exact: ΔΦ = −log(C), the rotation vector of Cᵀ: θ = atan2(‖s‖/2, (tr C − 1)/2) with
///   s = vee(Cᵀ − C) = (C(2,3) − C(3,2), C(3,1) − C(1,3), C(1,2) − C(2,1)), ΔΦ = θ/(2 sin θ)·s
///   (θ/(2 sin θ) by its Taylor series 1/2 + θ²/12 + 7θ⁴/720 for θ < 1e-4).
///
/// Sources: shared/spec/deflection.md §2 and §4 (observation and its signs); the log map and
/// Rodrigues' formula of SO(3): T. D. Barfoot, State Estimation for Robotics (CUP 2017), ch. 7
/// (matrix Lie groups); the psi-angle error convention: P. G. Savage, Strapdown Analytics (2000).
///
/// Units: radians. Errors: InputError (field as given by the caller, e.g. "samples[12].lgu")
/// for a non-finite matrix, one that is not orthogonal within the tolerance, or one with
/// determinant −1 (a reflection).

#include <string>

#include <Eigen/Core>

namespace meridian::dov {

/// Small angles of the attitude difference (radians), axes of the n frame.
struct AttitudeDifference {
  double east_rad = 0.0;   ///< ΔΦ_E, about the east axis
  double north_rad = 0.0;  ///< ΔΦ_N, about the north axis
  double up_rad = 0.0;     ///< ΔΦ_U, about the up axis
  /// (ΔΦ_E, ΔΦ_N, ΔΦ_U).
  Eigen::Vector3d vector() const { return {east_rad, north_rad, up_rad}; }
};

/// How ΔΦ is taken from C_{n′}^{n}.
enum class Extraction {
  Exact,          ///< −log(C), the exact rotation vector (default)
  SkewSymmetric,  ///< C(2,3), C(3,1), C(1,2) (1-based), the spec's small-angle form
};

/// Default orthogonality tolerance: max |(CᵀC − I)_ij| ≤ 1e-8, i.e. a spurious angle of at most
/// about 1e-8 rad (0.002″) in ΔΦ. Matrices printed with 12 significant digits pass.
inline constexpr double kOrthogonalityTolerance = 1e-8;

/// Throws InputError naming `field` unless m is finite, max |(mᵀm − I)_ij| ≤ tolerance and
/// det m > 0. `tolerance` must be finite and > 0 (InputError otherwise).
void check_rotation(const Eigen::Matrix3d& m, const std::string& field,
                    double tolerance = kOrthogonalityTolerance);

/// C_{n′}^{n} = lgu_body_to_nav · ins_body_to_nav ᵀ (C_b^n of LGU/GNSS, C_b^{n′} of INS/GNSS).
/// No checks (call check_rotation on the inputs first).
Eigen::Matrix3d attitude_difference_matrix(const Eigen::Matrix3d& lgu_body_to_nav,
                                           const Eigen::Matrix3d& ins_body_to_nav);

/// Skew-symmetric small-angle extraction (file comment): ΔΦ_E = C(2,3), ΔΦ_N = C(3,1),
/// ΔΦ_U = C(1,2), 1-based. No checks.
AttitudeDifference skew_symmetric_part(const Eigen::Matrix3d& c);

/// Exact extraction ΔΦ = −log(C) for a rotation C (file comment). Throws InputError naming
/// `field` when the rotation angle is within 1e-6 rad of π (the axis is then ill-defined; an
/// attitude difference is never that large). No orthogonality check (call check_rotation).
AttitudeDifference rotation_vector(const Eigen::Matrix3d& c, const std::string& field = {});

/// ΔΦ by `method`.
AttitudeDifference extract(const Eigen::Matrix3d& c, Extraction method,
                           const std::string& field = {});

/// The rotation exp(−[ΔΦ×]) (Rodrigues' formula): the inverse of rotation_vector, used by the
/// simulator. Exact for any angle.
Eigen::Matrix3d rotation_from_difference(const AttitudeDifference& d);

/// Cross-product matrix [a×] (file comment).
Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& a);

}  // namespace meridian::dov
