#include "meridian/maglev/model.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "meridian/adjust/least_squares.hpp"
#include "meridian/core/angle.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"

namespace meridian::maglev {
namespace {
ErrorContext field(const char* f) { return ErrorContext{{}, std::nullopt, f}; }

void require(const Uncertain& u, const char* name) {
  if (!std::isfinite(u.value) || !std::isfinite(u.sigma) || u.sigma < 0.0)
    throw InputError(fmt::format("{} must be finite with a σ ≥ 0", name), field(name));
}

double wrap(double a) {
  double w = std::fmod(a, 2.0 * units::kPi);
  if (w < 0.0) w += 2.0 * units::kPi;
  return w;
}
}  // namespace

Uncertain directive_amplitude(Uncertain K, double latitude_rad) {
  require(K, "scale");
  if (!(K.value > 0.0)) throw InputError("the scale K must be > 0", field("scale"));
  if (!std::isfinite(latitude_rad) || std::abs(latitude_rad) >= units::kPi / 2)
    throw InputError("the latitude must be within ±90° (exclusive)", field("latitude"));
  const double f = units::kEarthRotationRate_rad_s * std::cos(latitude_rad);
  return {K.value * f, K.sigma * f};
}

TwoPositionSolution two_position(Uncertain m1, Uncertain m2, Uncertain K, double latitude_rad,
                                 Uncertain r1) {
  return two_position(m1, m2, 0.0, K, latitude_rad, r1);
}

TwoPositionSolution two_position(Uncertain m1, Uncertain m2, double c12, Uncertain K,
                                 double latitude_rad, Uncertain r1) {
  require(m1, "mean1");
  require(m2, "mean2");
  require(r1, "circle_reading");
  const Uncertain A = directive_amplitude(K, latitude_rad);
  TwoPositionSolution s;
  s.ratio = (m1.value - m2.value) / (2.0 * A.value);
  if (!(std::abs(s.ratio) <= 1.0))
    throw NumericalError(
        fmt::format(
            "|(I1 − I2)/(2·K·ω·cos φ)| = {:.6g} > 1: the position means ({:.9g} A, {:.9g} A) "
            "do not fit the scale K = {:.9g} A·s/rad at this latitude (check K, the latitude, "
            "or whether the positions are 180° apart{})",
            std::abs(s.ratio), m1.value, m2.value, K.value,
            std::abs(s.ratio) > 100.0 ? "; currents 1000× too large? values in mA under an [A] "
                                        "header"
                                      : ""),
        field("alpha1"));
  const double a = std::asin(s.ratio);
  const double ca = std::cos(a);
  if (!std::isfinite(c12) || std::abs(c12) > m1.sigma * m2.sigma * (1.0 + 1e-12))
    throw InputError("the covariance of the means exceeds their σ", field("mean1"));
  const double v = m1.sigma * m1.sigma + m2.sigma * m2.sigma;
  const double s_means = std::sqrt(std::max(0.0, v - 2.0 * c12));
  const double s_sum = std::sqrt(std::max(0.0, v + 2.0 * c12));
  // |ratio| = 1 exactly: cos α = 0, the σ is unbounded; report it as a numerical failure.
  if (ca <= 0.0)
    throw NumericalError("α1 = ±90°: the position means give no usable direction", field("alpha1"));
  const double sa_means = s_means / (2.0 * A.value * ca);
  const double sa_k = std::tan(a) * K.sigma / K.value;
  s.alpha1_rad = {a, std::hypot(sa_means, sa_k)};
  s.north_rad = {wrap(r1.value - a), std::hypot(r1.sigma, s.alpha1_rad.sigma)};
  s.bias_A = {0.5 * (m1.value + m2.value), 0.5 * s_sum};
  return s;
}

CoarseSolution coarse_seek(const std::vector<CoarsePosition>& positions, Uncertain K,
                           double latitude_rad, Uncertain r1, std::optional<Uncertain> bias) {
  require(r1, "circle_reading");
  for (const auto& p : positions) {
    require(p.mean_A, "mean");
    if (!std::isfinite(p.offset_rad))
      throw InputError("a position offset is not finite", field("offset"));
  }
  const Uncertain A = directive_amplitude(K, latitude_rad);
  CoarseSolution out;
  if (positions.empty())
    throw InputError("coarse seeking needs at least one position", field("positions"));
  if (positions.size() == 1) {
    if (!bias) throw InputError("one coarse position needs an assumed bias b", field("bias"));
    require(*bias, "bias");
    const auto& p = positions[0];
    const double ratio = (p.mean_A.value - bias->value) / A.value;
    if (!(std::abs(ratio) < 1.0))
      throw NumericalError(fmt::format("|(I − b)/(K·ω·cos φ)| = {:.6g} ≥ 1", std::abs(ratio)),
                           field("alpha1"));
    const double phi = std::asin(ratio);  // α_1 + θ
    const double a = std::remainder(phi - p.offset_rad, 2.0 * units::kPi);
    const double sig = std::hypot(p.mean_A.sigma, bias->sigma) / (A.value * std::cos(phi));
    const double sig_k = std::abs(std::tan(phi)) * K.sigma / K.value;
    out.alpha1_rad = {a, std::hypot(sig, sig_k)};
    out.bias_A = *bias;
  } else if (positions.size() == 2) {
    const double d =
        std::remainder(positions[1].offset_rad - positions[0].offset_rad, 2.0 * units::kPi);
    if (std::abs(std::abs(d) - units::kPi) > 1e-9)
      throw InputError("two coarse positions must be 180° apart (or give three or more)",
                       field("positions"));
    const auto s =
        two_position(positions[0].mean_A, positions[1].mean_A, K, latitude_rad, {0.0, 0.0});
    out.alpha1_rad = {
        std::remainder(s.alpha1_rad.value - positions[0].offset_rad, 2.0 * units::kPi),
        s.alpha1_rad.sigma};
    out.bias_A = s.bias_A;
  } else {
    const auto n = static_cast<Eigen::Index>(positions.size());
    Eigen::MatrixXd Am(n, 3);
    Eigen::VectorXd l(n), sig(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto& p = positions[static_cast<std::size_t>(i)];
      if (!(p.mean_A.sigma > 0.0))
        throw InputError("coarse position means need a σ > 0", field("mean"));
      Am(i, 0) = std::cos(p.offset_rad);  // s = A sin α
      Am(i, 1) = std::sin(p.offset_rad);  // c = A cos α
      Am(i, 2) = 1.0;
      l(i) = p.mean_A.value;
      sig(i) = p.mean_A.sigma;
    }
    const auto r = adjust::solve_linear_diagonal(Am, l, sig);
    const double s = r.x(0), c = r.x(1);
    const double a2 = s * s + c * c;
    // α = atan2(s, c): ∂α/∂s = c/a², ∂α/∂c = −s/a².
    const Eigen::Vector2d g(c / a2, -s / a2);
    const double var = g.dot(r.cofactor.topLeftCorner(2, 2) * g);
    const Eigen::Vector2d h(s / std::sqrt(a2), c / std::sqrt(a2));
    out.alpha1_rad = {std::atan2(s, c), std::sqrt(var)};
    out.amplitude_A =
        Uncertain{std::sqrt(a2), std::sqrt(h.dot(r.cofactor.topLeftCorner(2, 2) * h))};
    out.bias_A = {r.x(2), std::sqrt(r.cofactor(2, 2))};
  }
  out.north_rad = {wrap(r1.value - out.alpha1_rad.value),
                   std::hypot(r1.sigma, out.alpha1_rad.sigma)};
  return out;
}

}  // namespace meridian::maglev
