#include "meridian/gravity/coefficients.hpp"

#include <algorithm>
#include <string>

#include "meridian/core/error.hpp"

namespace meridian::gravity {

SphericalHarmonicCoefficients::SphericalHarmonicCoefficients(int max_degree, int max_order)
    : SphericalHarmonicCoefficients(max_degree, max_order, Unfilled{}) {
  std::fill(c_.begin(), c_.end(), 0.0);
  std::fill(s_.begin(), s_.end(), 0.0);
}

SphericalHarmonicCoefficients::SphericalHarmonicCoefficients(int max_degree, int max_order, Unfilled)
    : n_(max_degree), m_(max_order) {
  if (max_degree < 0 || max_order < 0 || max_order > max_degree)
    throw InputError("invalid degree/order " + std::to_string(max_degree) + "/" + std::to_string(max_order) +
                     " (need 0 <= order <= degree)");
  const std::size_t count = index(n_, m_) + 1;
  c_.resize(count);
  s_.resize(count);
  std::fill_n(s_.begin(), static_cast<std::size_t>(n_) + 1, 0.0);  // S̄_n0
}

SphericalHarmonicCoefficients SphericalHarmonicCoefficients::truncated(int max_degree, int max_order) const {
  const int n = max_degree < 0 ? n_ : std::min(max_degree, n_);
  const int m = std::min(max_order < 0 ? n : max_order, std::min(n, m_));
  SphericalHarmonicCoefficients out(n, m);
  for (int mm = 0; mm <= m; ++mm)
    for (int nn = mm; nn <= n; ++nn) out.set(nn, mm, c(nn, mm), s(nn, mm));
  return out;
}

}  // namespace meridian::gravity
