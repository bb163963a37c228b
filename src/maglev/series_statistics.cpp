#include "meridian/maglev/series_statistics.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::maglev {
namespace {
void require_series(std::span<const double> x, std::size_t min_n) {
  if (x.size() < min_n)
    throw InputError(fmt::format("{} samples are too few (at least {} needed)", x.size(), min_n));
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!std::isfinite(x[i])) throw InputError(fmt::format("sample {} is not a finite number", i));
}

double lag_product(std::span<const double> x, double mean, std::size_t k) {
  double s = 0.0;
  const std::size_t n = x.size();
  for (std::size_t i = 0; i + k < n; ++i) s += (x[i] - mean) * (x[i + k] - mean);
  return s / static_cast<double>(n);
}
}  // namespace

std::vector<double> autocovariance(std::span<const double> x, double mean, int max_lag) {
  if (max_lag < 0 || static_cast<std::size_t>(max_lag) >= x.size())
    throw InputError(fmt::format("lag {} is not possible for {} samples", max_lag, x.size()));
  std::vector<double> g(static_cast<std::size_t>(max_lag) + 1);
  for (std::size_t k = 0; k < g.size(); ++k) g[k] = lag_product(x, mean, k);
  return g;
}

LongRunVariance long_run_variance(std::span<const double> acov) {
  if (acov.empty()) throw InputError("no autocovariance");
  LongRunVariance r;
  r.gamma0 = acov[0];
  double sum = 0.0;
  std::size_t m = 0;
  for (; 2 * m + 1 < acov.size(); ++m) {
    const double pair = acov[2 * m] + acov[2 * m + 1];
    if (pair <= 0.0) break;
    sum += pair;
    r.lags = static_cast<int>(2 * m + 1);
  }
  r.truncated = 2 * m + 1 >= acov.size();
  r.long_run = m == 0 ? r.gamma0 : -r.gamma0 + 2.0 * sum;
  if (r.long_run < 0.0) r.long_run = 0.0;
  return r;
}

MeanEstimate mean_with_autocorrelation(std::span<const double> x) {
  require_series(x, 2);
  MeanEstimate e;
  e.n = x.size();
  double s = 0.0;
  for (double v : x) s += v;
  e.mean = s / static_cast<double>(e.n);
  // Lags on demand: pair sums until the first non-positive one.
  const std::size_t cap =
      std::min<std::size_t>(e.n - 1, static_cast<std::size_t>(kMaxLongRunLag) + 1);
  const double g0 = lag_product(x, e.mean, 0);
  e.variance = g0;
  double sum = 0.0;
  bool stopped = false;
  std::size_t k = 0;
  while (k + 1 <= cap) {
    const double pair = (k == 0 ? g0 : lag_product(x, e.mean, k)) + lag_product(x, e.mean, k + 1);
    if (pair <= 0.0) {
      stopped = true;
      break;
    }
    sum += pair;
    e.lags = static_cast<int>(k + 1);
    k += 2;
  }
  e.lag_limit_reached = !stopped && e.n - 1 > cap;
  const double n = static_cast<double>(e.n);
  double lr = e.lags == 0 ? g0 : -g0 + 2.0 * sum;
  if (g0 <= 0.0) {
    e.n_eff = n;
    e.sigma = 0.0;
    return e;
  }
  e.n_eff = std::clamp(n * g0 / std::max(lr, g0 / n), 1.0, n);
  e.sigma = std::sqrt(g0 / e.n_eff);
  return e;
}

double median(std::span<const double> x) {
  if (x.empty()) throw InputError("the median of no values");
  std::vector<double> a(x.begin(), x.end());
  const std::size_t h = a.size() / 2;
  std::nth_element(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(h), a.end());
  const double upper = a[h];
  if (a.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(h)));
}

Uncertain huber_mean(std::span<const double> x, double n_eff, double k) {
  require_series(x, 2);
  if (!(k > 0.0) || !std::isfinite(k)) throw InputError("the Huber tuning constant must be > 0");
  const double med = median(x);
  std::vector<double> dev(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) dev[i] = std::abs(x[i] - med);
  const double s = 1.4826 * median(dev);
  if (s <= 0.0) return {med, 0.0};
  const double c = k * s;
  // Iterate on deviations from the median (no cancellation against a large offset).
  double mu = 0.0;
  bool converged = false;
  for (int it = 0; it < 100; ++it) {
    double num = 0.0, den = 0.0;
    for (double v : x) {
      const double y = v - med;
      const double r = y - mu;
      const double w = std::abs(r) <= c ? 1.0 : c / std::abs(r);
      num += w * y;
      den += w;
    }
    const double next = num / den;
    const double step = std::abs(next - mu);
    mu = next;
    if (step <= 1e-10 * s) {
      converged = true;
      break;
    }
  }
  if (!converged) throw NumericalError("the Huber mean did not converge in 100 iterations");
  mu += med;
  double psi2 = 0.0, dpsi = 0.0;
  for (double v : x) {
    const double u = (v - mu) / s;
    const double p = std::clamp(u, -k, k);
    psi2 += p * p;
    if (std::abs(u) <= k) dpsi += 1.0;
  }
  const double n = static_cast<double>(x.size());
  psi2 /= n;
  dpsi /= n;
  if (dpsi <= 0.0) throw NumericalError("the Huber mean has no samples inside its tuning range");
  const double neff = std::clamp(n_eff, 1.0, n);
  return {mu, std::sqrt(s * s * psi2 / (dpsi * dpsi) / neff)};
}

double stability(std::span<const double> values) {
  require_series(values, 2);
  double m = 0.0;
  for (double v : values) m += v;
  m /= static_cast<double>(values.size());
  double s = 0.0;
  for (double v : values) s += (v - m) * (v - m);
  return std::sqrt(s / static_cast<double>(values.size() - 1));
}

}  // namespace meridian::maglev
