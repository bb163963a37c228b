#pragma once
/// \file orientations.hpp
/// Two (or more) independent orientations of the same underground line —
/// separate campaigns, each with its own calibration on the known line — and
/// the rule of the coal-mine surveying regulations for them (spec §7.1): the
/// grid azimuths differ by no more than the limit (40″ for a 15″-class
/// instrument) and the σ of their mean is within ±10″ (regulations.hpp).
///
///   campaign files → io::run_orientation_files → gyro::combine_orientations → OrientationsResult

#include <string>
#include <vector>

#include "meridian/gyro/calibration.hpp"
#include "meridian/gyro/campaign.hpp"
#include "meridian/gyro/regulations.hpp"

namespace meridian::gyro {

struct OrientationsResult {
  std::string station, target;             ///< names of the line's end points
  std::vector<std::string> files;          ///< each orientation's CampaignInput::file
  std::vector<Uncertain> grid_azimuths_rad;  ///< T of each orientation, as given
  /// Mean T. sigma_propagated = sqrt(ΣᵢΣⱼ C_ij)/n with C the covariance
  /// below; the σ used (mean.sigma) = sqrt(max(σ_own, σ_empirical)² + σ_shared²):
  /// the orientations' own parts bounded below by their scatter
  /// sqrt(Σv²/(n(n−1))) (= |T2 − T1|/2 for two), plus what they share, which
  /// the scatter cannot show. Without shared sources: the larger of the
  /// propagated sqrt(Σσ²)/n and the empirical σ.
  AzimuthMean mean;
  /// C_ij (rad²): σ_i² on the diagonal, Σ c_i·c_j over shared error sources off it.
  std::vector<std::vector<double>> covariance_rad2;
  double sigma_own_propagated_rad = 0;   ///< sqrt(Σ(σ_i² − shared parts of σ_i²))/n
  double sigma_shared_rad = 0;           ///< sqrt(ΣΣ C_ij − own)/n: the part common to all
  double sigma_if_independent_rad = 0;   ///< sqrt(Σσ_i²)/n, for comparison
  std::vector<std::string> shared_sources;  ///< "known line azimuth (known_line.azimuth (grid))", "eta (…)"
  RegulationLimits limits;                 ///< the limits the checks used
  std::vector<Check> checks;               ///< largest difference; σ of the mean
  std::vector<std::string> notes;
  bool all_checks_pass() const;
};

/// Two orientations' points are the same when within this distance (m): a station mark is
/// re-occupied to a few millimetres; 5 cm leaves room for coordinates rounded or re-computed.
inline constexpr double kSamePointTolerance_m = 0.05;

/// Distance (m) between two points from their latitudes and longitudes (a sphere of 6371 km;
/// for the few metres that matter here exact to 0.5 %).
double point_distance_m(const PointResult& a, const PointResult& b);

/// Whether two error sources are one (error_sources.hpp: kind, source text,
/// value within 0.001″, points within kSamePointTolerance_m).
bool same_error_source(const ErrorSource& a, const ErrorSource& b);

/// cov(T_a, T_b) (rad²) through the error sources the two campaigns share.
double shared_covariance_rad2(const CampaignResult& a, const CampaignResult& b);

/// Combine the results of independent orientations of one line (at least
/// two). The line is the same when the stations (and the targets, where both
/// have one) lie within kSamePointTolerance_m of orientation 1's, whatever
/// their names (names that differ after NFKC, core/unicode.hpp, give a note);
/// a target missing in one is compared by name after NFKC. The σ of the mean
/// holds the error sources the orientations share (their known line, the
/// deflection at the same points; error_sources.hpp) as correlated. Each orientation must pass its own checks (a check per
/// orientation); the limits are the tightest of the orientations' (their
/// classes and tolerances). A run whose gyro observations are another
/// orientation's (same_observations: a copied book, reused calibration runs)
/// fails the check "no run of another orientation" (field "orientations[j]").
/// Throws InputError when fewer than two results are given, or when they are
/// not of the same line (naming the point and the distance).
OrientationsResult combine_orientations(const std::vector<CampaignResult>& orientations);

}  // namespace meridian::gyro
