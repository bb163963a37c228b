#include "meridian/gyro/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "meridian/core/angle.hpp"
#include "meridian/core/error.hpp"

namespace meridian::gyro {

AzimuthMean mean_direction(const std::vector<Uncertain>& v) {
  if (v.empty()) throw InputError("no values to average");
  AzimuthMean m;
  m.count = static_cast<int>(v.size());
  const double n = static_cast<double>(v.size());
  std::vector<double> x;
  double var = 0;
  for (const auto& u : v) {
    x.push_back(v[0].value + wrap_signed_rad(u.value - v[0].value));
    var += u.sigma * u.sigma;
  }
  double mean = 0;
  for (double xi : x) mean += xi;
  mean /= n;
  m.sigma_propagated = std::sqrt(var) / n;
  if (v.size() >= 2) {
    double vv = 0;
    for (double xi : x) vv += (xi - mean) * (xi - mean);
    m.sigma_empirical = std::sqrt(vv / (n * (n - 1.0)));
    m.one_run_sigma = std::sqrt(vv / (n - 1.0));
    const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
    m.max_difference = *hi - *lo;
  } else {
    m.sigma_empirical = std::numeric_limits<double>::quiet_NaN();
    m.one_run_sigma = std::numeric_limits<double>::quiet_NaN();
  }
  double sigma = m.sigma_propagated;
  if (std::isfinite(m.sigma_empirical) && m.sigma_empirical > sigma) sigma = m.sigma_empirical;
  m.mean = {wrap_positive_rad(mean), sigma};
  return m;
}

InstrumentConstantResult instrument_constant(Uncertain known, const std::vector<Uncertain>& before,
                                             const std::vector<Uncertain>& after,
                                             double tolerance_rad) {
  if (before.empty() && after.empty())
    throw InputError("no gyro determination on the known line", {"", std::nullopt, "calibration"});
  InstrumentConstantResult r;
  r.tolerance_rad = tolerance_rad;
  auto constants = [&](const std::vector<Uncertain>& g) {
    std::vector<Uncertain> e;
    for (const auto& a : g) e.push_back({wrap_signed_rad(known.value - a.value), a.sigma});
    return e;
  };
  r.before = constants(before);
  r.after = constants(after);
  std::vector<Uncertain> all = r.before;
  all.insert(all.end(), r.after.begin(), r.after.end());
  // Mean of the gyro-only part; σ(A_known) is common to every E_i.
  const AzimuthMean m = mean_direction(all);
  r.mean = {wrap_signed_rad(m.mean.value), std::hypot(m.mean.sigma, known.sigma)};
  if (!r.before.empty() && !r.after.empty()) {
    const double b = wrap_signed_rad(mean_direction(r.before).mean.value);
    const double a = wrap_signed_rad(mean_direction(r.after).mean.value);
    r.difference_rad = wrap_signed_rad(a - b);
    r.within_tolerance = std::fabs(*r.difference_rad) <= tolerance_rad;
    if (!r.within_tolerance)
      r.warnings.push_back(fmt::format(
          "instrument constant changed by {:.1f}\" between before and after (tolerance {:.1f}\")",
          Angle::radians(*r.difference_rad).arcsec(), Angle::radians(tolerance_rad).arcsec()));
  } else {
    r.warnings.push_back("instrument constant observed only " +
                         std::string(r.before.empty() ? "after" : "before") +
                         " the unknown line: its stability is not checked");
  }
  return r;
}

}  // namespace meridian::gyro
