#include "meridian/maglev/stationarity.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "meridian/adjust/statistics.hpp"
#include "meridian/core/error.hpp"
#include "meridian/maglev/series_statistics.hpp"

namespace meridian::maglev {

std::vector<std::size_t> StationarityResult::rejected() const {
  std::vector<std::size_t> r;
  for (std::size_t i = 0; i < segments.size(); ++i)
    if (!segments[i].kept) r.push_back(i);
  return r;
}

StationarityResult test_stationarity(std::span<const double> x, const StationarityOptions& o) {
  const std::size_t n = x.size();
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(x[i])) throw InputError(fmt::format("sample {} is not a finite number", i));
  if (!(o.alpha > 0.0 && o.alpha < 1.0))
    throw InputError(fmt::format("significance level {} is not in (0, 1)", o.alpha),
                     ErrorContext{{}, std::nullopt, "alpha"});
  const std::size_t L =
      o.segment_length == 0 ? std::max<std::size_t>(64, n / 20) : o.segment_length;
  if (L < 32)
    throw InputError(fmt::format("segment length {} is too short (at least 32 samples)", L),
                     ErrorContext{{}, std::nullopt, "segment_length"});
  if (n < 2 * L)
    throw InputError(fmt::format("{} samples are too few for two segments of {} (segments need "
                                 "at least 32 samples: use shorter segments, or no processing "
                                 "for plain means of all samples)",
                                 n, L),
                     ErrorContext{{}, std::nullopt, "segment_length"});
  const int M = o.autocovariance_lags;
  if (M < 1 || static_cast<std::size_t>(M) >= L / 4)
    throw InputError(
        fmt::format("{} autocovariance lags are not possible with segments of {} (1 … {})", M, L,
                    L / 4 - 1),
        ErrorContext{{}, std::nullopt, "autocovariance_lags"});
  // Lags of the reference autocovariance: enough for the long-run variance, at most L/4.
  const int J = static_cast<int>(std::min<std::size_t>(L / 4, 200));

  StationarityResult r;
  r.segment_length = L;
  std::size_t begin = 0;
  while (begin < n) {
    std::size_t end = std::min(n, begin + L);
    if (n - end < L / 2) end = n;  // a short remainder joins this segment
    SegmentTest s;
    s.begin = begin;
    s.end = end;
    r.segments.push_back(s);
    begin = end;
  }
  const std::size_t S = r.segments.size();
  // Bonferroni over the S segments and the two tests of each.
  r.segment_alpha = o.family_wise ? o.alpha / (2.0 * static_cast<double>(S)) : o.alpha;
  std::vector<std::vector<double>> acov(S);
  for (std::size_t i = 0; i < S; ++i) {
    auto& s = r.segments[i];
    const auto seg = x.subspan(s.begin, s.end - s.begin);
    double sum = 0.0;
    for (double v : seg) sum += v;
    s.mean = sum / static_cast<double>(seg.size());
    acov[i] = autocovariance(seg, s.mean, J);
  }
  // Robust start: medians over the segments.
  std::vector<double> tmp(S);
  for (std::size_t i = 0; i < S; ++i) tmp[i] = r.segments[i].mean;
  double mu = median(tmp);
  std::vector<double> gamma(static_cast<std::size_t>(J) + 1);
  for (std::size_t k = 0; k < gamma.size(); ++k) {
    for (std::size_t i = 0; i < S; ++i) tmp[i] = acov[i][k];
    gamma[k] = median(tmp);
  }
  std::vector<char> kept(S, 1), previous;
  std::size_t n_kept = n;
  // Pass 1: σ²_LR by robust batch means, median of m_s·(x̄_s − μ)² over the median of χ²(1)
  // (0.454936): a minority of disturbed segments cannot inflate it.
  double long_run = 0.0;
  for (std::size_t i = 0; i < S; ++i) {
    const auto& s = r.segments[i];
    tmp[i] = static_cast<double>(s.end - s.begin) * (s.mean - mu) * (s.mean - mu);
  }
  long_run = median(tmp) / 0.454936;
  // Degrees of freedom of σ²_LR for the t test of the means: pass 1 batch means by the MAD (about
  // 37 % efficient), later n/(2K) for a flat-top sum over K lags (Priestley 1981, §6.2.3).
  double long_run_dof = std::max(1.0, 0.37 * static_cast<double>(S));
  // γ for Bartlett's covariance of the segment autocovariances: pass 1 the lag-wise medians,
  // later the autocovariance of the kept samples about their common mean (segment means not
  // removed, which would hide the low-frequency part).
  std::vector<double> bartlett_gamma = gamma;
  const std::size_t dim = static_cast<std::size_t>(M) + 1;
  std::vector<double> concat;
  concat.reserve(n);
  for (int pass = 1; pass <= 20; ++pass) {
    r.passes = pass;
    // Bartlett's covariance of sample autocovariances (γ_{−j} = γ_j, 0 beyond the sequence):
    // m·Cov(γ̂_k, γ̂_l) = Σ_j γ_j·γ_{j+l−k} + γ_{j+l}·γ_{j−k}.
    const long JB = static_cast<long>(bartlett_gamma.size()) - 1;
    auto g = [&](long j) {
      const auto a = static_cast<std::size_t>(std::labs(j));
      return a < bartlett_gamma.size() ? bartlett_gamma[a] : 0.0;
    };
    Eigen::MatrixXd W(dim, dim);
    for (int k = 0; k <= M; ++k)
      for (int l = k; l <= M; ++l) {
        double s = 0.0;
        for (long j = -JB - M; j <= JB + M; ++j) s += g(j) * g(j + l - k) + g(j + l) * g(j - k);
        W(k, l) = W(l, k) = s;
      }
    // Delta method to (log γ_0, γ_k/γ_0): W' = J·W·Jᵀ.
    if (gamma[0] > 0.0) {
      Eigen::MatrixXd jac = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(dim),
                                                static_cast<Eigen::Index>(dim));
      jac(0, 0) = 1.0 / gamma[0];
      for (std::size_t k = 1; k < dim; ++k) {
        const auto kk = static_cast<Eigen::Index>(k);
        jac(kk, 0) = -gamma[k] / (gamma[0] * gamma[0]);
        jac(kk, kk) = 1.0 / gamma[0];
      }
      W = (jac * W * jac.transpose()).eval();
    }
    // Mahalanobis form through the eigen-decomposition; directions with a negligible variance
    // (a numerically singular W) are left out of the form and of the degrees of freedom.
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(W);
    const Eigen::VectorXd lam = eig.eigenvalues();
    const double lam_max = lam.size() > 0 ? lam.maxCoeff() : 0.0;
    for (std::size_t i = 0; i < S; ++i) {
      auto& s = r.segments[i];
      const double m = static_cast<double>(s.end - s.begin);
      const double frac = 1.0 / m + (kept[i] ? -1.0 : 1.0) / static_cast<double>(n_kept);
      const double var = long_run * std::max(frac, 1.0 / m * 1e-3);
      s.z_mean = var > 0.0 ? (s.mean - mu) / std::sqrt(var) : (s.mean == mu ? 0.0 : HUGE_VAL);
      s.p_mean = std::isfinite(s.z_mean)
                     ? adjust::student_t_two_sided_probability(s.z_mean, long_run_dof)
                     : 0.0;
      // Compared: log γ_0 and the autocorrelations γ_k/γ_0 (k = 1…M), nearer to normal than the
      // autocovariances (a variance estimate of a short correlated segment is skewed).
      Eigen::VectorXd d(dim);
      const double g0s = acov[i][0];
      d(0) = g0s > 0.0 ? std::log(g0s / gamma[0]) : -HUGE_VAL;
      for (std::size_t k = 1; k < dim; ++k)
        d(static_cast<Eigen::Index>(k)) = g0s > 0.0 ? acov[i][k] / g0s - gamma[k] / gamma[0] : 0.0;
      const Eigen::VectorXd u = eig.eigenvectors().transpose() * d;
      double q = 0.0;
      int used = 0;
      for (Eigen::Index k = 0; k < lam.size(); ++k)
        if (lam(k) > 1e-12 * lam_max) {
          q += u(k) * u(k) * m / lam(k);
          ++used;
        }
      if (!std::isfinite(d(0))) q = HUGE_VAL;
      s.q_autocovariance = q;
      s.p_autocovariance =
          !std::isfinite(q) ? 0.0
          : used > 0        ? adjust::chi_squared_upper_probability(q, static_cast<double>(used))
                            : 1.0;
      s.mean_passed = s.p_mean >= r.segment_alpha;
      s.autocovariance_passed = s.p_autocovariance >= r.segment_alpha;
      s.kept = s.mean_passed && s.autocovariance_passed;
    }
    previous = kept;
    for (std::size_t i = 0; i < S; ++i) kept[i] = r.segments[i].kept ? 1 : 0;
    r.long_run_variance = long_run;
    // New reference from the kept segments.
    n_kept = 0;
    double sum = 0.0;
    std::fill(gamma.begin(), gamma.end(), 0.0);
    concat.clear();
    for (std::size_t i = 0; i < S; ++i) {
      if (!kept[i]) continue;
      const auto& s = r.segments[i];
      const std::size_t m = s.end - s.begin;
      n_kept += m;
      sum += s.mean * static_cast<double>(m);
      for (std::size_t k = 0; k < gamma.size(); ++k)
        gamma[k] += acov[i][k] * static_cast<double>(m);
      concat.insert(concat.end(), x.begin() + static_cast<std::ptrdiff_t>(s.begin),
                    x.begin() + static_cast<std::ptrdiff_t>(s.end));
    }
    if (n_kept == 0)
      throw NumericalError(fmt::format(
          "no stable segment: all {} segments of {} samples fail the stationarity tests at α = {}",
          S, L, o.alpha));
    mu = sum / static_cast<double>(n_kept);
    for (double& gk : gamma) gk /= static_cast<double>(n_kept);
    r.reference_mean = mu;
    r.reference_autocovariance = gamma;
    r.kept_samples = n_kept;
    // σ²_LR of the kept samples as one series (series_statistics.hpp), and their autocovariance
    // about the common mean up to a few times its truncation lag for Bartlett's covariance.
    if (concat.size() >= 2) {
      const MeanEstimate me = mean_with_autocorrelation(concat);
      long_run = me.sigma * me.sigma * static_cast<double>(me.n);
      r.correlation_time_samples = me.variance > 0.0 ? long_run / me.variance : 1.0;
      long_run_dof = std::max(1.0, static_cast<double>(me.n) / (2.0 * std::max(me.lags, 1)));
      const int lags = static_cast<int>(std::min<std::size_t>(
          concat.size() - 1, static_cast<std::size_t>(std::max(2 * me.lags + 2, 2 * M + 2))));
      bartlett_gamma = autocovariance(concat, me.mean, lags);
    }
    if (kept == previous) break;
  }
  return r;
}

}  // namespace meridian::maglev
