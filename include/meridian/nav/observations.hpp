#pragma once
/// \file observations.hpp
/// The observations of a marine navigation line (shared/spec/navigation.md §1, §2, §5, §7;
/// docs/navigation.md): dead-reckoning velocity samples, shore stations, lines of position
/// (LOPs) and satellite fixes, in a local plane.
///
/// Frame: the plane of the job, x = north, y = east, metres (a map grid such as UTM or a local
/// transverse Mercator, or coordinates given directly). Readers turn geographic coordinates
/// into this plane (geodesy/grid.hpp) and true velocities into grid velocities; the numerics
/// never see latitudes. Directions are azimuths clockwise from the x (north) axis. Times are
/// seconds on one time scale (the reader's choice, e.g. seconds of the day or since an epoch).
#include <cstddef>
#include <string>

#include <Eigen/Core>

namespace meridian::nav {

/// One dead-reckoning sample: the velocity over ground of the interval that ends at time_s
/// (spec §1: Δx_i = Δt_i·v_i·cos α_i, Δy_i = Δt_i·v_i·sin α_i with Δt_i = t_i − t_{i−1}).
struct DrSample {
  double time_s = 0.0;       ///< end of the interval (s); strictly increasing along a line
  double v_north_m_s = 0.0;  ///< v·cos α (m/s)
  double v_east_m_s = 0.0;   ///< v·sin α (m/s)
  /// Covariance of (v_north, v_east) (m²/s²), symmetric, ≥ 0: the white random part of the
  /// velocity error only (a bias is what the methods estimate).
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
};

/// A DR sample from speed v (m/s, ≥ 0) and heading α (rad, clockwise from north) with
/// independent white errors σ_v (m/s) and σ_α (rad): v_N = v·cos α, v_E = v·sin α and the
/// first-order covariance J·diag(σ_v², σ_α²)·Jᵀ, J = ∂(v_N, v_E)/∂(v, α). Throws InputError
/// for a non-finite value or a negative speed or σ.
DrSample dr_from_speed_heading(double time_s, double speed_m_s, double heading_rad,
                               double sigma_speed_m_s, double sigma_heading_rad);

/// A shore station (transmitter) of a radio positioning system.
struct Station {
  std::string name;         ///< as the user writes it in the LOP file
  double x_north_m = 0.0;   ///< plane coordinates (m)
  double y_east_m = 0.0;
};

/// Kind of a line of position (spec §2).
enum class LopType {
  Range,            ///< L = d(P, S₁) (m)
  RangeDifference,  ///< L = d(P, S₁) − d(P, S₂) (m): hyperbolic; a time difference τ (s) is
                    ///< converted by the reader as L = c·τ with the chain's propagation speed c
};

/// A chain of a radio system with its optional unknown parameters (spec §2, §4.3): the LOPs of
/// the chain are modelled as L = (1 + scale)·d + offset, d the geometric range or range
/// difference. Parameters not estimated are zero. Prior σ of an estimated parameter: its
/// uncertainty before the line (large: the data determine it).
struct Chain {
  std::string name;
  bool estimate_scale = false;      ///< unknown scale factor (dimensionless)
  bool estimate_offset = false;     ///< unknown constant offset (m): also an initial lane error
  double sigma_scale_prior = 1e-3;  ///< > 0
  double sigma_offset_prior_m = 1000.0;  ///< > 0
};

/// One LOP observation.
struct Lop {
  double time_s = 0.0;
  LopType type = LopType::Range;
  std::size_t station = 0;   ///< index into Input::stations (S₁)
  std::size_t station2 = 0;  ///< S₂ for RangeDifference; ignored for Range
  double value_m = 0.0;      ///< observed L (m)
  double sigma_m = 0.0;      ///< σ of L (m), > 0
  /// Index into Input::chains, or kNoChain when the LOP has no chain parameters.
  std::size_t chain = kNoChain;
  static constexpr std::size_t kNoChain = static_cast<std::size_t>(-1);
};

/// A satellite fix (spec §5): a position with its covariance, e.g. from $--GGA.
struct Fix {
  double time_s = 0.0;
  double x_north_m = 0.0;
  double y_east_m = 0.0;
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();  ///< (m²), positive definite
};

/// The known position at a time (simulations, or withheld fixes of a real line).
struct TruthPoint {
  double time_s = 0.0;
  double x_north_m = 0.0;
  double y_east_m = 0.0;
};

}  // namespace meridian::nav
