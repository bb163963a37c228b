#pragma once
/// \file euler.hpp
/// An attitude matrix C_b^n from heading, pitch and roll, for lines that give Euler angles
/// instead of matrices (io/dov_files.hpp: the columns lgu_heading_deg, lgu_pitch_deg,
/// lgu_roll_deg and ins_…).
///
/// Convention (the one of dov/simulator.hpp and of most ENU strapdown texts):
/// * n: the ENU frame of attitude_difference.hpp (rows E, N, U) — for the INS/GNSS solution
///   its n′ (up along the plumb line);
/// * b: body axes x to the right, y forward, z up (RFU);
/// * heading ψ: clockwise from north to the forward axis (ψ = 90°: heading east), any value;
///   pitch θ: forward axis above the horizontal positive, |θ| ≤ 90°; roll φ: the right side
///   down positive;
/// * the z-x-y sequence: C_b^n = R_z(−ψ)·R_x(θ)·R_y(φ), with R_a(α) the right-handed rotation
///   by α about axis a of the current frame (R_z(α) = [[cos α, −sin α, 0], [sin α, cos α, 0],
///   [0, 0, 1]], …). Written out (c = cos, s = sin):
///
///       [ cψ·cφ + sψ·sθ·sφ    sψ·cθ    cψ·sφ − sψ·sθ·cφ ]
///       [ −sψ·cφ + cψ·sθ·sφ   cψ·cθ   −sψ·sφ − cψ·sθ·cφ ]
///       [ −cθ·sφ              sθ       cθ·cφ            ]
///
///   so the forward axis is (sψ·cθ, cψ·cθ, sθ) in ENU and the right axis has the up
///   component −cθ·sφ.
///
/// Units: radians. Sources: the rotation matrices of D. H. Titterton & J. L. Weston,
/// Strapdown Inertial Navigation Technology, 2nd ed. (IET 2004), §3.6 (Euler angles), with
/// the ENU/RFU axes and sequence stated above. No errors: any finite angles give a rotation;
/// non-finite angles give a non-finite matrix (which the workflow's checks reject).

#include <Eigen/Core>

namespace meridian::dov {

/// C_b^n of heading ψ, pitch θ, roll φ (radians) by the convention of the file comment.
Eigen::Matrix3d body_to_nav_from_euler(double heading_rad, double pitch_rad, double roll_rad);

}  // namespace meridian::dov
