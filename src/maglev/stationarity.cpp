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

namespace {

// L, after checking the series and the options (see the file comment's errors).
std::size_t checked_segment_length(std::span<const double> x, const StationarityOptions& o) {
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
  return L;
}

// Consecutive segments of L samples; a remainder shorter than L/2 joins the last one.
std::vector<SegmentTest> split_into_segments(std::size_t n, std::size_t L) {
  std::vector<SegmentTest> segments;
  std::size_t begin = 0;
  while (begin < n) {
    std::size_t end = std::min(n, begin + L);
    if (n - end < L / 2) end = n;  // a short remainder joins this segment
    SegmentTest s;
    s.begin = begin;
    s.end = end;
    segments.push_back(s);
    begin = end;
  }
  return segments;
}

// Each segment's mean (into the segment) and autocovariance about it, lags 0 … J.
std::vector<std::vector<double>> segment_autocovariances(std::span<const double> x,
                                                         std::vector<SegmentTest>& segments,
                                                         int J) {
  std::vector<std::vector<double>> acov(segments.size());
  for (std::size_t i = 0; i < segments.size(); ++i) {
    auto& s = segments[i];
    const auto seg = x.subspan(s.begin, s.end - s.begin);
    double sum = 0.0;
    for (double v : seg) sum += v;
    s.mean = sum / static_cast<double>(seg.size());
    acov[i] = autocovariance(seg, s.mean, J);
  }
  return acov;
}

// The reference a pass tests the segments against: the position's stable state.
struct Reference {
  double mean = 0.0;                   ///< μ
  std::vector<double> gamma;           ///< γ_0 … γ_J
  double long_run = 0.0;               ///< σ²_LR
  double long_run_dof = 1.0;           ///< its degrees of freedom (t test of the means)
  std::vector<double> bartlett_gamma;  ///< γ of Bartlett's covariance
  std::size_t n_kept = 0;              ///< N, samples in the reference
};

// Pass 1: medians over the segments, so that a minority of disturbed segments cannot pull it.
Reference robust_start(const std::vector<SegmentTest>& segments,
                       const std::vector<std::vector<double>>& acov, int J, std::size_t n) {
  const std::size_t S = segments.size();
  Reference ref;
  std::vector<double> tmp(S);
  for (std::size_t i = 0; i < S; ++i) tmp[i] = segments[i].mean;
  ref.mean = median(tmp);
  ref.gamma.assign(static_cast<std::size_t>(J) + 1, 0.0);
  for (std::size_t k = 0; k < ref.gamma.size(); ++k) {
    for (std::size_t i = 0; i < S; ++i) tmp[i] = acov[i][k];
    ref.gamma[k] = median(tmp);
  }
  // σ²_LR by robust batch means, median of m_s·(x̄_s − μ)² over the median of χ²(1) (0.454936).
  for (std::size_t i = 0; i < S; ++i) {
    const auto& s = segments[i];
    tmp[i] = static_cast<double>(s.end - s.begin) * (s.mean - ref.mean) * (s.mean - ref.mean);
  }
  ref.long_run = median(tmp) / 0.454936;
  // Degrees of freedom of σ²_LR: batch means by the MAD are about 37 % efficient (later n/(2K)
  // for a flat-top sum over K lags, Priestley 1981, §6.2.3).
  ref.long_run_dof = std::max(1.0, 0.37 * static_cast<double>(S));
  // γ of Bartlett's covariance: the lag-wise medians (later the autocovariance of the kept
  // samples about their common mean; segment means not removed, which would hide the
  // low-frequency part).
  ref.bartlett_gamma = ref.gamma;
  ref.n_kept = n;
  return ref;
}

// The covariance of u_s times the segment length: Bartlett's covariance of sample
// autocovariances (γ_{−j} = γ_j, 0 beyond the sequence),
// m·Cov(γ̂_k, γ̂_l) = Σ_j γ_j·γ_{j+l−k} + γ_{j+l}·γ_{j−k}, taken by the delta method to
// (log γ_0, γ_k/γ_0): W' = J·W·Jᵀ.
Eigen::MatrixXd autocovariance_test_covariance(const Reference& ref, int M) {
  const std::vector<double>& bg = ref.bartlett_gamma;
  const long JB = static_cast<long>(bg.size()) - 1;
  auto g = [&](long j) {
    const auto a = static_cast<std::size_t>(std::labs(j));
    return a < bg.size() ? bg[a] : 0.0;
  };
  const std::size_t dim = static_cast<std::size_t>(M) + 1;
  Eigen::MatrixXd W(dim, dim);
  for (int k = 0; k <= M; ++k)
    for (int l = k; l <= M; ++l) {
      double s = 0.0;
      for (long j = -JB - M; j <= JB + M; ++j) s += g(j) * g(j + l - k) + g(j + l) * g(j - k);
      W(k, l) = W(l, k) = s;
    }
  const std::vector<double>& gamma = ref.gamma;
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
  return W;
}

// The autocovariance test's covariance in its eigen-decomposition; directions with a negligible
// variance (a numerically singular covariance) are left out of the form and of the degrees of
// freedom.
struct AutocovarianceTest {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig;
  double lam_max = 0.0;
  explicit AutocovarianceTest(const Eigen::MatrixXd& W) : eig(W) {
    lam_max = eig.eigenvalues().size() > 0 ? eig.eigenvalues().maxCoeff() : 0.0;
  }
};

// Both tests of one segment against the reference; `in_reference`: the segment was kept in the
// last pass (part of the reference's N samples).
void test_segment(SegmentTest& s, const std::vector<double>& acov, bool in_reference,
                  const Reference& ref, const AutocovarianceTest& t, double alpha) {
  const double m = static_cast<double>(s.end - s.begin);
  const double frac = 1.0 / m + (in_reference ? -1.0 : 1.0) / static_cast<double>(ref.n_kept);
  const double var = ref.long_run * std::max(frac, 1.0 / m * 1e-3);
  s.z_mean = var > 0.0 ? (s.mean - ref.mean) / std::sqrt(var) : (s.mean == ref.mean ? 0.0 : HUGE_VAL);
  s.p_mean = std::isfinite(s.z_mean)
                 ? adjust::student_t_two_sided_probability(s.z_mean, ref.long_run_dof)
                 : 0.0;
  // Compared: log γ_0 and the autocorrelations γ_k/γ_0 (k = 1…M), nearer to normal than the
  // autocovariances (a variance estimate of a short correlated segment is skewed).
  const Eigen::VectorXd& lam = t.eig.eigenvalues();
  const auto dim = static_cast<std::size_t>(lam.size());
  Eigen::VectorXd d(dim);
  const double g0s = acov[0];
  d(0) = g0s > 0.0 ? std::log(g0s / ref.gamma[0]) : -HUGE_VAL;
  for (std::size_t k = 1; k < dim; ++k)
    d(static_cast<Eigen::Index>(k)) = g0s > 0.0 ? acov[k] / g0s - ref.gamma[k] / ref.gamma[0] : 0.0;
  const Eigen::VectorXd u = t.eig.eigenvectors().transpose() * d;
  double q = 0.0;
  int used = 0;
  for (Eigen::Index k = 0; k < lam.size(); ++k)
    if (lam(k) > 1e-12 * t.lam_max) {
      q += u(k) * u(k) * m / lam(k);
      ++used;
    }
  if (!std::isfinite(d(0))) q = HUGE_VAL;
  s.q_autocovariance = q;
  s.p_autocovariance = !std::isfinite(q) ? 0.0
                       : used > 0 ? adjust::chi_squared_upper_probability(q, static_cast<double>(used))
                                  : 1.0;
  s.mean_passed = s.p_mean >= alpha;
  s.autocovariance_passed = s.p_autocovariance >= alpha;
  s.kept = s.mean_passed && s.autocovariance_passed;
}

// The reference of the next pass from the segments kept: their mean and length-weighted mean
// autocovariance; σ²_LR of the kept samples as one series (series_statistics.hpp) and their
// autocovariance about the common mean, up to a few times its truncation lag, for Bartlett's
// covariance. Records the reference in r. Throws NumericalError when no segment is kept.
void update_reference(std::span<const double> x, const std::vector<char>& kept,
                      const std::vector<std::vector<double>>& acov, const StationarityOptions& o,
                      Reference& ref, StationarityResult& r) {
  const int M = o.autocovariance_lags;
  ref.n_kept = 0;
  double sum = 0.0;
  std::fill(ref.gamma.begin(), ref.gamma.end(), 0.0);
  std::vector<double> concat;
  concat.reserve(x.size());
  for (std::size_t i = 0; i < r.segments.size(); ++i) {
    if (!kept[i]) continue;
    const auto& s = r.segments[i];
    const std::size_t m = s.end - s.begin;
    ref.n_kept += m;
    sum += s.mean * static_cast<double>(m);
    for (std::size_t k = 0; k < ref.gamma.size(); ++k)
      ref.gamma[k] += acov[i][k] * static_cast<double>(m);
    concat.insert(concat.end(), x.begin() + static_cast<std::ptrdiff_t>(s.begin),
                  x.begin() + static_cast<std::ptrdiff_t>(s.end));
  }
  if (ref.n_kept == 0)
    throw NumericalError(fmt::format(
        "no stable segment: all {} segments of {} samples fail the stationarity tests at α = {}",
        r.segments.size(), r.segment_length, o.alpha));
  ref.mean = sum / static_cast<double>(ref.n_kept);
  for (double& gk : ref.gamma) gk /= static_cast<double>(ref.n_kept);
  r.reference_mean = ref.mean;
  r.reference_autocovariance = ref.gamma;
  r.kept_samples = ref.n_kept;
  if (concat.size() < 2) return;
  const MeanEstimate me = mean_with_autocorrelation(concat);
  ref.long_run = me.sigma * me.sigma * static_cast<double>(me.n);
  r.correlation_time_samples = me.variance > 0.0 ? ref.long_run / me.variance : 1.0;
  ref.long_run_dof = std::max(1.0, static_cast<double>(me.n) / (2.0 * std::max(me.lags, 1)));
  const int lags = static_cast<int>(std::min<std::size_t>(
      concat.size() - 1, static_cast<std::size_t>(std::max(2 * me.lags + 2, 2 * M + 2))));
  ref.bartlett_gamma = autocovariance(concat, me.mean, lags);
}

}  // namespace

StationarityResult test_stationarity(std::span<const double> x, const StationarityOptions& o) {
  const std::size_t L = checked_segment_length(x, o);
  // Lags of the reference autocovariance: enough for the long-run variance, at most L/4.
  const int J = static_cast<int>(std::min<std::size_t>(L / 4, 200));
  StationarityResult r;
  r.segment_length = L;
  r.segments = split_into_segments(x.size(), L);
  const std::size_t S = r.segments.size();
  // Bonferroni over the S segments and the two tests of each.
  r.segment_alpha = o.family_wise ? o.alpha / (2.0 * static_cast<double>(S)) : o.alpha;
  const auto acov = segment_autocovariances(x, r.segments, J);
  Reference ref = robust_start(r.segments, acov, J, x.size());
  std::vector<char> kept(S, 1), previous;
  // Test against the reference, then make the kept segments the reference, until the kept set
  // repeats.
  for (int pass = 1; pass <= 20; ++pass) {
    r.passes = pass;
    const AutocovarianceTest t(autocovariance_test_covariance(ref, o.autocovariance_lags));
    for (std::size_t i = 0; i < S; ++i)
      test_segment(r.segments[i], acov[i], kept[i] != 0, ref, t, r.segment_alpha);
    previous = kept;
    for (std::size_t i = 0; i < S; ++i) kept[i] = r.segments[i].kept ? 1 : 0;
    r.long_run_variance = ref.long_run;
    update_reference(x, kept, acov, o, ref, r);
    if (kept == previous) break;
  }
  return r;
}

}  // namespace meridian::maglev
