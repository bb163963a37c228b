#pragma once
/// \file statistics.hpp
/// Statistical tests of adjustments and filters, and the distribution functions they use —
/// the one home of these for all of Meridian (gyro fits, variance-component estimation,
/// Kalman-filter innovation gating).
///
/// Distribution functions come from Boost.Math (boost/math/distributions; relative accuracy
/// near machine precision); nothing here hand-codes a quantile. They never return NaN:
/// arguments out of range throw InputError, and a failure inside Boost is reported as
/// NumericalError.
///
/// Conventions: α is a significance level (probability of rejecting a true null hypothesis),
/// 0 < α < 1. Degrees of freedom ν are real and ≥ 1 (integers for an adjustment's redundancy;
/// real values for the redundancy of a variance-component group). The tests assume the
/// a-priori σ0 = 1 of least_squares.hpp, i.e. Σ_ll is the full covariance of the
/// observations in their own units. Residuals follow least_squares.hpp: v = A·x̂ − l, so
/// an observation that is too large by ∇ gets a negative v_i and w_i.
///
/// Sources: Baarda (1968) A testing procedure for use in geodetic networks, Netherlands
/// Geodetic Commission, Publications on Geodesy 2(5); Teunissen (2006) Testing theory: an
/// introduction, 2nd ed., VSSD Delft (the overall model test and the w-test); Koch (1999)
/// Parameter estimation and hypothesis testing in linear models, 2nd ed., Springer, ch. 4;
/// Bar-Shalom, Li & Kirubarajan (2001) Estimation with applications to tracking and
/// navigation, Wiley (filter consistency: the NIS χ² test and gating).

#include <vector>

#include <Eigen/Dense>

#include "meridian/adjust/least_squares.hpp"

namespace meridian::adjust {

// ---------------------------------------------------------------------------------------------
// Distribution functions (Boost.Math).

/// Upper quantile of the χ² distribution with ν degrees of freedom: the x ≥ 0 with
/// P(X > x) = α, X ~ χ²(ν) (e.g. ν = 10, α = 0.01: 23.2093). Throws InputError unless
/// 0 < α < 1 and ν ≥ 1 (finite).
double chi_squared_upper_quantile(double alpha, double dof);

/// Upper-tail probability P(X > x) of χ²(ν), x ≥ 0 (the p-value of a statistic x); in
/// [0, 1]. chi_squared_upper_quantile(chi_squared_upper_probability(x, ν), ν) = x where
/// the probability is in (0, 1). Throws InputError unless x is finite and ≥ 0 and ν ≥ 1.
double chi_squared_upper_probability(double x, double dof);

/// Two-sided critical value of the standard normal distribution: k = Φ⁻¹(1 − α/2), so
/// P(|Z| > k) = α, Z ~ N(0, 1) (α = 0.05: 1.959964; α = 0.001: 3.290527). Throws
/// InputError unless 0 < α < 1.
double normal_two_sided_critical(double alpha);

/// Two-sided tail probability P(|Z| > |z|) = 2·(1 − Φ(|z|)) = erfc(|z|/√2) of N(0, 1); in
/// [0, 1] (z = 3: 0.0026998). Throws InputError for a non-finite z.
double normal_two_sided_probability(double z);

/// Two-sided critical value of Student's t with ν degrees of freedom: P(|T| > k) = α (for the
/// test of a mean against a reference with an estimated variance). Throws InputError unless
/// 0 < α < 1 and ν ≥ 1.
double student_t_two_sided_critical(double alpha, double dof);

/// Two-sided tail probability P(|T| > |t|) of Student's t(ν); in [0, 1]. Throws InputError
/// for a non-finite t or ν < 1.
double student_t_two_sided_probability(double t, double dof);

/// Upper quantile of Fisher's F(ν1, ν2): P(F > x) = α (for ratios of independent variance
/// estimates, e.g. two variance components or two models' σ̂0²). Throws InputError unless
/// 0 < α < 1 and ν1, ν2 ≥ 1.
double fisher_f_upper_quantile(double alpha, double dof1, double dof2);

/// Upper-tail probability P(F > x) of F(ν1, ν2), x ≥ 0; in [0, 1]. Throws InputError unless
/// x is finite and ≥ 0 and ν1, ν2 ≥ 1.
double fisher_f_upper_probability(double x, double dof1, double dof2);

// ---------------------------------------------------------------------------------------------
// Global (overall) model test.

/// The global model test of an adjustment: H0 "the functional and stochastic models hold with
/// σ0 = 1" against "σ0 > 1" (blunders, model errors or too optimistic σ). T = vᵀPv ~ χ²(dof)
/// under H0 (Koch ch. 4; Teunissen, the overall model test); H0 is rejected when
/// T > χ²_{1−α}(dof).
///
/// One-sided (upper tail) by choice: only a too-large vᵀPv points to errors in the
/// observations or the model; a too-small one (σ̂0 ≪ 1, σ given too pessimistically) is seen
/// in sigma0 and p_value (close to 1). For the two-sided test use chi_squared_upper_quantile
/// at α/2 and 1 − α/2.
struct GlobalTestResult {
  double vtpv = 0.0;            ///< test statistic T = vᵀPv (dimensionless), ≥ 0
  int dof = 0;                  ///< degrees of freedom n − u, ≥ 1
  double sigma0 = 0.0;          ///< a-posteriori σ̂0 = sqrt(T/dof)
  double alpha = 0.0;           ///< significance level of the test
  double critical_value = 0.0;  ///< χ²_{1−α}(dof): upper quantile at α
  double p_value = 0.0;         ///< P(χ²(dof) > T), in [0, 1]
  bool rejected = false;        ///< T > critical_value: H0 rejected at α
};

/// The global test of T = vᵀPv with dof degrees of freedom at significance α.
/// Throws InputError unless vtpv is finite and ≥ 0, dof ≥ 1 (no redundancy: nothing to test)
/// and 0 < α < 1.
GlobalTestResult global_test(double vtpv, int dof, double alpha);

/// The global test of an adjustment (its vtpv and dof; also a NonlinearResult). Throws as
/// above, e.g. InputError when result.dof = 0.
GlobalTestResult global_test(const LeastSquaresResult& result, double alpha);

/// χ² gate: true (accept) when statistic ≤ χ²_{1−α}(dof) — the one-sided test of
/// global_test without σ̂0 and p-value. For a Kalman filter the statistic is the normalised
/// innovation squared NIS = νᵀ·S⁻¹·ν of an innovation ν with covariance S, dof = dim ν
/// (Bar-Shalom et al.); in a loop, compute the limit once with chi_squared_upper_quantile.
/// Throws InputError unless statistic is finite and ≥ 0, dof ≥ 1 and 0 < α < 1.
bool chi_squared_gate(double statistic, double dof, double alpha);

// ---------------------------------------------------------------------------------------------
// w-test (data snooping).

/// Result of Baarda's w-test of every observation: H0 "no outlier" against "an outlier in
/// observation i alone", rejected when |w_i| > k (two-sided, w_i ~ N(0, 1) under H0).
/// Observations with an undefined w_i (NaN: not controlled) are skipped.
///
/// One pass only. In Baarda's data snooping the observation with the largest |w| is removed
/// (when rejected) and the adjustment repeated; the other entries of `rejected` are
/// candidates, not proven blunders.
struct DataSnoopingResult {
  double critical_value = 0.0;  ///< k, > 0
  double alpha0 = 0.0;          ///< two-sided significance of k per observation: P(|Z| > k)
  std::vector<int> rejected;    ///< indices i with |w_i| > k, ascending (0-based)
  int tested = 0;               ///< observations with a defined w_i
  int largest_index = -1;       ///< index of the largest |w_i| (first of equals); −1 if none
  double largest_w = 0.0;       ///< w at largest_index, signed (0 when none tested)
};

/// w-test of the statistics w (dimensionless, ~N(0,1) under H0, NaN = skipped), e.g.
/// LeastSquaresResult::w_statistics or a subset of it, with the critical value k.
/// k = 3.29 is α0 = 0.1 % (Baarda's B-method), k = 3.0 is α0 ≈ 0.27 %.
/// Throws InputError unless k is finite and > 0, or when a w_i is ±∞.
DataSnoopingResult w_test(const Eigen::VectorXd& w, double critical_value);

/// Data snooping of an adjustment at the two-sided significance α0 per observation:
/// w_test(result.w_statistics, normal_two_sided_critical(α0)) (Baarda 1968).
/// Throws InputError unless 0 < α0 < 1.
DataSnoopingResult data_snooping(const LeastSquaresResult& result, double alpha0);

}  // namespace meridian::adjust
