#pragma once
/// \file drift.hpp
/// Level per position + common drift on one clock (maglev-gyro spec §3a).
///
/// The positions are measured one after the other on the instrument's clock, so a slow drift
/// d(t) of the rotor current does not cancel in Ī₁ − Ī₂. All kept samples of all position blocks
/// are fitted jointly:
///
///   I(t_j) = μ_{p(j)} + d_1·u_j + d_2·u_j² + e_j,   u_j = (t_j − t_ref)/h          (D1)
///
/// μ_1, μ_2 the levels of the two positions at t_ref (A), d_1 (A per h seconds), d_2 (quadratic,
/// optional), t_ref the mean time of the samples fitted, h half their time span (conditioning
/// only). Ordinary least squares; its covariance from the long-run variance of the residuals
/// taken in time order (series_statistics.hpp, Geyer), Cov(β̂) = σ²_LR·(XᵀX)⁻¹·n_eff/(n_eff − p):
/// for regressors that vary slowly against the noise's correlation time (block indicators,
/// low-order polynomials) XᵀΣX ≈ σ²_LR·XᵀX, and OLS is then asymptotically as efficient as GLS
/// (Grenander & Rosenblatt 1957, polynomial regression with stationary errors), without an AR
/// order to choose; the factor n_eff/(n_eff − p) makes up for the variance the fit takes out of
/// the residuals. Joined blocks err on the safe side (the correlation across a gap is smaller).
///
/// The separation of drift and azimuth is judged by the variance inflation of Δ = μ_1 − μ_2:
/// VIF = Var(Δ̂ | drift fitted)/Var(Δ̂ | no drift), both with the same σ²_LR. One block per
/// position gives VIF ≥ 4 (σ at least doubled: only the slopes within the blocks see the drift);
/// symmetric sequences (1-2-1, 1-2-2-1) give VIF near 1.
///
/// Units: s, A. Errors: InputError for a mask, time and value of different lengths, fewer
/// samples than parameters + 2; NumericalError ("drift") when the normal matrix is singular.

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "meridian/core/uncertain.hpp"
#include "meridian/maglev/series.hpp"

namespace meridian::maglev {

/// The drift term of (D1).
enum class DriftModel { none, linear, quadratic };
/// "none" | "linear" | "quadratic". Throws InputError for another name.
DriftModel drift_model_from_string(const std::string& name);
const char* to_string(DriftModel m);
/// Polynomial order of the drift (0, 1, 2).
int drift_order(DriftModel m);

/// A run of consecutive samples of one position on the common clock.
struct TimeBlock {
  int position = 1;             ///< 1 or 2
  std::size_t begin = 0;        ///< first sample in that position's series (0-based)
  std::size_t end = 0;          ///< one past the last
  double begin_s = 0.0, end_s = 0.0;  ///< times of the first and the last sample
};

/// The blocks of the two positions in time order (the samples merged by time; a pause of more
/// than 10 median sample intervals also starts a block, so 1-2-2-1 is four blocks). Empty when the
/// positions do not share one clock: a time that occurs in both, more than 64 blocks or a block
/// of fewer than 8 samples (two series on their own clocks, each starting at 0, interleave).
std::vector<TimeBlock> time_blocks(const PositionSeries& p1, const PositionSeries& p2);

/// "1-2-2-1".
std::string block_sequence(const std::vector<TimeBlock>& blocks);

/// What the joint fit of one (D1) gives.
struct LevelDriftFit {
  int order = 0;                  ///< drift order fitted
  double reference_time_s = 0.0;  ///< t_ref
  double half_span_s = 1.0;       ///< h
  Eigen::VectorXd beta;           ///< μ_1, μ_2, d_1, d_2 (as many as the order)
  Eigen::MatrixXd covariance;     ///< of beta, A² (σ²_LR·(XᵀX)⁻¹·n_eff/(n_eff − p))
  double long_run_variance_A2 = 0.0;  ///< σ²_LR of the residuals (per sample)
  double n_eff = 0.0;             ///< of the residuals taken as one series
  std::size_t samples = 0;
  double vif_difference = 1.0;    ///< Var(Δ̂)/Var(Δ̂ without drift)
  std::vector<double> residuals_A;  ///< in time order (block by block)
  /// Drift value d_1·u + d_2·u² at time t (A); 0 for order 0.
  double drift_at(double t_s) const;
  /// Rate of the drift at t (A/s).
  Uncertain rate_at(double t_s) const;
};

/// The samples fitted: the two positions' series, which of their samples count (mask 1), the
/// values to fit (e.g. the cleaned series) and the blocks in time order.
struct LevelDriftData {
  const PositionSeries* position1 = nullptr;
  const PositionSeries* position2 = nullptr;
  std::span<const double> values1, values2;  ///< same lengths as the series
  std::span<const char> mask1, mask2;        ///< 1: fitted
  const std::vector<TimeBlock>* blocks = nullptr;
};

/// Fit (D1) with the drift of `order` (see the file comment). Throws as the file comment says.
LevelDriftFit fit_levels_and_drift(const LevelDriftData& data, int order);

}  // namespace meridian::maglev
