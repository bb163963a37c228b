#include "meridian/maglev/settling.hpp"

#include <algorithm>
#include <cmath>

#include "meridian/adjust/statistics.hpp"

namespace meridian::maglev {

std::vector<double> settling_time_constants(double duration_s, std::size_t samples) {
  std::vector<double> g;
  const double dt = samples > 1 ? duration_s / static_cast<double>(samples - 1) : duration_s;
  for (double tau : {1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0})
    if (tau < duration_s / 3.0 && tau >= 3.0 * dt) g.push_back(tau);
  return g;
}

std::optional<SettlingCut> detect_settling(std::span<const double> t, std::span<const double> r,
                                           double lrv, double level_sigma, double alpha) {
  const std::size_t n = std::min(t.size(), r.size());
  if (n < 8 || !(lrv > 0.0) || !(level_sigma > 0.0)) return std::nullopt;
  const double T = t[n - 1] - t[0];
  double rbar = 0.0;
  for (std::size_t i = 0; i < n; ++i) rbar += r[i] / static_cast<double>(n);
  SettlingCut best;
  double best_abs_z = -1.0;
  std::vector<double> g(n);
  for (double tau : settling_time_constants(T, n)) {
    double gbar = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      g[i] = std::exp(-(t[i] - t[0]) / tau);
      gbar += g[i] / static_cast<double>(n);
    }
    double sxx = 0.0, sxy = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      sxx += (g[i] - gbar) * (g[i] - gbar);
      sxy += (g[i] - gbar) * (r[i] - rbar);
    }
    if (!(sxx > 0.0)) continue;
    const double a = sxy / sxx;
    const double z = a / std::sqrt(lrv / sxx);
    if (std::abs(z) > best_abs_z) {
      best_abs_z = std::abs(z);
      best.amplitude_A = a;
      best.tau_s = tau;
      best.z = z;
    }
  }
  if (best_abs_z < 0.0 || adjust::normal_two_sided_probability(best.z) >= alpha) return std::nullopt;
  best.detected = true;
  best.block_begin_s = t[0];
  const double ratio = std::abs(best.amplitude_A) * best.tau_s / (T * 0.1 * level_sigma);
  best.cut_s = ratio > 1.0 ? best.tau_s * std::log(ratio) : 0.0;
  if (best.cut_s > 0.5 * T) {
    best.cut_s = 0.5 * T;
    best.limited = true;
  }
  return best;
}

}  // namespace meridian::maglev
