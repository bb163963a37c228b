#include "meridian/geodesy/azimuth_chain.hpp"

#include <cmath>

#include <fmt/format.h>

#include "meridian/core/checks.hpp"
#include "meridian/core/angle.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/geodesy/frames.hpp"
#include "meridian/geodesy/laplace.hpp"

namespace meridian::geodesy {
namespace {

void require_sigma(double s, const char* what) {
  if (!std::isfinite(s) || s < 0)
    throw InputError(
        fmt::format("standard deviation of {} must be finite and >= 0 (got {})", what, s));
}

void check(AzimuthKind kind, const Uncertain& v, const AzimuthReduction& r) {
  const std::string what = to_string(kind) + " azimuth";
  require_finite(v.value, what.c_str());
  require_sigma(v.sigma, what.c_str());
  require_finite(r.latitude_rad, "latitude");
  if (std::abs(r.latitude_rad) > units::kPi / 2)
    throw InputError(fmt::format("latitude {} rad ({} deg) must satisfy |lat| <= 90 deg",
                                 r.latitude_rad, units::rad_to_deg(r.latitude_rad)));
  if (r.eta_rad) require_sigma(r.eta_rad->sigma, "eta");
  if (r.xi_rad) {
    if (!r.eta_rad)
      throw InputError("xi given without eta: the Laplace equation needs eta (its first term)");
    const double xi = r.xi_rad->value;
    if (!std::isfinite(xi) || std::abs(xi) > kMaxDeflection_rad)
      throw InputError(
          fmt::format("deflection component xi = {} rad ({}\") is not finite or exceeds 0.01 rad; "
                      "is it in radians?",
                      xi, units::rad_to_arcsec(xi)));
    require_sigma(r.xi_rad->sigma, "xi");
  }
  if (r.zenith_distance_rad) check_zenith_distance(*r.zenith_distance_rad);
  require_finite(r.convergence_rad, "meridian convergence");
  if (r.arc_to_chord_rad) require_finite(*r.arc_to_chord_rad, "arc-to-chord correction");
}

// The exact steps: record γ and δ.
void record_grid_terms(const AzimuthReduction& r, AzimuthSteps& s) {
  s.convergence_rad = r.convergence_rad;
  if (r.arc_to_chord_rad) {
    s.arc_to_chord_rad = *r.arc_to_chord_rad;
    s.arc_to_chord_applied = true;
  }
}

// T = (α − γ) + δ, in this order (byte-identical outputs).
double grid_from_geodetic(double alpha, const AzimuthReduction& r) {
  double t = alpha - r.convergence_rad;
  if (r.arc_to_chord_rad) t += *r.arc_to_chord_rad;
  return t;
}

bool zenith_term(const AzimuthReduction& r) {
  return r.eta_rad && r.xi_rad && r.zenith_distance_rad;
}

// −(ξ·sin α − η·cos α)·cot z at the geodetic azimuth α.
double zenith_correction(const AzimuthReduction& r, double alpha) {
  return laplace_zenith_correction_rad(r.xi_rad->value, r.eta_rad->value, alpha,
                                       *r.zenith_distance_rad);
}

// σ of the Laplace step with the zenith-distance term at α: η is in both
// terms, ∂α/∂η = −tan φ + cos α·cot z, ∂α/∂ξ = −sin α·cot z.
double sigma_with_zenith_term(double sigma_given, const AzimuthReduction& r, double alpha) {
  const double cot_z = 1.0 / std::tan(*r.zenith_distance_rad);
  const double d_eta = std::tan(r.latitude_rad) - std::cos(alpha) * cot_z;
  const double d_xi = std::sin(alpha) * cot_z;
  return std::hypot(std::hypot(sigma_given, d_eta * r.eta_rad->sigma), d_xi * r.xi_rad->sigma);
}

// Inverse Laplace step: A = α − (−η·tan φ) = α + η·tan φ, σ_A = hypot(σ_α, σ_η·tan φ);
// with the zenith-distance term A = (α + η·tan φ) − c_z(α).
Uncertain astronomic_from_geodetic(Uncertain alpha, const AzimuthReduction& r, AzimuthSteps& s) {
  if (!r.eta_rad) return alpha;
  s.laplace_correction_rad = laplace_correction_rad(r.eta_rad->value, r.latitude_rad);
  s.laplace_applied = true;
  if (!zenith_term(r))
    return {alpha.value - s.laplace_correction_rad,
            std::hypot(alpha.sigma, r.eta_rad->sigma * std::tan(r.latitude_rad))};
  s.zenith_correction_rad = zenith_correction(r, alpha.value);
  s.zenith_term_applied = true;
  return {alpha.value - s.laplace_correction_rad - s.zenith_correction_rad,
          sigma_with_zenith_term(alpha.sigma, r, alpha.value)};
}

// Forward with the zenith-distance term: α = A + c_η + c_z(α), solved by
// fixed-point iteration from α₀ = A + c_η (contraction ≤ θ·|cot z| ≤ 0.08).
double solve_geodetic(double a, double c_eta, const AzimuthReduction& r, AzimuthSteps& s) {
  double cz = zenith_correction(r, a + c_eta);
  for (int i = 0; i < 100; ++i) {
    const double next = zenith_correction(r, (a + c_eta) + cz);
    // Rounding of α (ulp 9e-16 near 2π) moves c_z by < 1e-16 at a contraction of 0.08.
    const bool done = std::abs(next - cz) <= 2e-16;
    cz = next;
    if (done) {
      s.zenith_correction_rad = cz;
      s.zenith_term_applied = true;
      return (a + c_eta) + cz;
    }
  }
  throw NumericalError("the zenith-distance term of the Laplace equation did not converge");
}

}  // namespace

std::string to_string(AzimuthKind kind) {
  switch (kind) {
    case AzimuthKind::Astronomic:
      return "astronomic";
    case AzimuthKind::Geodetic:
      return "geodetic";
    case AzimuthKind::Grid:
      return "grid";
  }
  throw InputError(fmt::format("unknown azimuth kind {}", static_cast<int>(kind)));
}

AzimuthSteps azimuth_from_astronomic(Uncertain astronomic_rad, const AzimuthReduction& r) {
  check(AzimuthKind::Astronomic, astronomic_rad, r);
  AzimuthSteps s;
  const double a = wrap_positive_rad(astronomic_rad.value);
  const double sa = astronomic_rad.sigma;
  s.astronomic_rad = {a, sa};
  double alpha = a, salpha = sa;
  if (r.eta_rad) {
    s.laplace_correction_rad = laplace_correction_rad(r.eta_rad->value, r.latitude_rad);
    s.laplace_applied = true;
    if (zenith_term(r)) {
      const double alpha_u = solve_geodetic(a, s.laplace_correction_rad, r, s);
      alpha = wrap_positive_rad(alpha_u);
      salpha = sigma_with_zenith_term(sa, r, alpha_u);
    } else {
      alpha = wrap_positive_rad(a + s.laplace_correction_rad);
      salpha = std::hypot(sa, std::tan(r.latitude_rad) * r.eta_rad->sigma);
    }
  }
  s.geodetic_rad = {alpha, salpha};
  record_grid_terms(r, s);
  s.grid_rad = {wrap_positive_rad(grid_from_geodetic(alpha, r)), salpha};
  return s;
}

AzimuthSteps azimuth_steps(AzimuthKind kind, Uncertain value_rad, const AzimuthReduction& r) {
  switch (kind) {
    case AzimuthKind::Astronomic:
      return azimuth_from_astronomic(value_rad, r);
    case AzimuthKind::Geodetic: {
      check(kind, value_rad, r);
      AzimuthSteps s;
      record_grid_terms(r, s);
      const Uncertain a = astronomic_from_geodetic(value_rad, r, s);
      s.astronomic_rad = {wrap_positive_rad(a.value), a.sigma};
      s.geodetic_rad = {wrap_positive_rad(value_rad.value), value_rad.sigma};
      s.grid_rad = {wrap_positive_rad(grid_from_geodetic(value_rad.value, r)), value_rad.sigma};
      return s;
    }
    case AzimuthKind::Grid: {
      check(kind, value_rad, r);
      AzimuthSteps s;
      record_grid_terms(r, s);
      // α = (T + γ) − δ, in this order (byte-identical outputs).
      double alpha = value_rad.value + r.convergence_rad;
      if (r.arc_to_chord_rad) alpha -= *r.arc_to_chord_rad;
      const Uncertain a = astronomic_from_geodetic({alpha, value_rad.sigma}, r, s);
      s.astronomic_rad = {wrap_positive_rad(a.value), a.sigma};
      s.geodetic_rad = {wrap_positive_rad(alpha), value_rad.sigma};
      s.grid_rad = {wrap_positive_rad(value_rad.value), value_rad.sigma};
      return s;
    }
  }
  throw InputError(fmt::format("unknown azimuth kind {}", static_cast<int>(kind)));
}

}  // namespace meridian::geodesy
