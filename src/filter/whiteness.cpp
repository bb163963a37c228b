#include "meridian/filter/whiteness.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "meridian/adjust/statistics.hpp"
#include "meridian/core/error.hpp"

namespace meridian::filter {

int ljung_box_default_lags(std::size_t samples, int max_lag) {
  return static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(std::max(max_lag, 0)),
                                                samples / 5));
}

LjungBox::LjungBox(int series, int max_lag) : m_(series), max_lag_(max_lag) {
  if (series < 1 || max_lag < 1)
    throw InputError(fmt::format("Ljung–Box: series ({}) and max_lag ({}) must be ≥ 1", series,
                                 max_lag));
  const auto m = static_cast<std::size_t>(m_);
  const auto h = static_cast<std::size_t>(max_lag_);
  sum_.assign(m, 0.0);
  lag_sum_.assign(m * (h + 1), 0.0);
  first_.assign(m * h, 0.0);
  last_.assign(m * h, 0.0);
}

void LjungBox::add(const double* values) {
  const auto h = static_cast<std::size_t>(max_lag_);
  for (int j = 0; j < m_; ++j) {
    const double e = values[j];
    if (!std::isfinite(e)) throw InputError(fmt::format("Ljung–Box: value {} is not finite", e));
    const auto js = static_cast<std::size_t>(j);
    double* lag = &lag_sum_[js * (h + 1)];
    const double* ring = &last_[js * h];
    lag[0] += e * e;
    // ring[(n − k) mod h] is e_{n−k} (0-based t = n is the value being added)
    for (std::size_t k = 1; k <= h && k <= n_; ++k) lag[k] += e * ring[(n_ - k) % h];
    sum_[js] += e;
    if (n_ < h) first_[js * h + n_] = e;
    last_[js * h + n_ % h] = e;
  }
  ++n_;
}

LjungBoxResult LjungBox::result(double alpha, int lags) const {
  if (!(alpha > 0.0 && alpha < 1.0))
    throw InputError(fmt::format("Ljung–Box: alpha must be in (0, 1), is {}", alpha));
  LjungBoxResult r;
  r.samples = n_;
  r.alpha = alpha;
  const int h = lags > 0 ? lags : ljung_box_default_lags(n_, max_lag_);
  if (h > max_lag_ || (h > 0 && static_cast<std::size_t>(h) >= n_))
    throw InputError(fmt::format("Ljung–Box: {} lags for {} values (at most {} and fewer than "
                                 "the values)",
                                 h, n_, max_lag_));
  if (h == 0) return r;  // too few values: not tested
  const auto hs = static_cast<std::size_t>(max_lag_);
  const double n = static_cast<double>(n_);
  for (int j = 0; j < m_; ++j) {
    const auto js = static_cast<std::size_t>(j);
    const double* lag = &lag_sum_[js * (hs + 1)];
    const double mean = sum_[js] / n;
    // Σ(e − ē)² and, per k, Σ_{t>k}(e_t − ē)(e_{t−k} − ē) = L_k − ē(Σ_{t>k} e_t +
    // Σ_{t≤n−k} e_t) + (n − k)ē², the partial sums from the first and last values.
    const double c0 = lag[0] - n * mean * mean;
    if (!(c0 > 0.0)) continue;  // a constant series has no autocorrelation to test
    double head = 0.0, tail = 0.0, sum_rho2 = 0.0;
    for (int k = 1; k <= h; ++k) {
      const auto ks = static_cast<std::size_t>(k);
      head += first_[js * hs + ks - 1];                 // e_1 … e_k
      tail += last_[js * hs + (n_ - ks) % hs];          // e_{n−k+1} … e_n
      const double ck = lag[ks] - mean * ((sum_[js] - head) + (sum_[js] - tail)) +
                        (n - static_cast<double>(k)) * mean * mean;
      const double rho = ck / c0;
      sum_rho2 += rho * rho / (n - static_cast<double>(k));
    }
    r.q += n * (n + 2.0) * sum_rho2;
  }
  r.lags = h;
  r.dof = static_cast<double>(m_) * h;
  r.critical_value = adjust::chi_squared_upper_quantile(alpha, r.dof);
  r.p_value = adjust::chi_squared_upper_probability(std::max(r.q, 0.0), r.dof);
  r.pass = r.q <= r.critical_value;
  return r;
}

}  // namespace meridian::filter
