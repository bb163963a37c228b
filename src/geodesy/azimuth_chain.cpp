#include "meridian/geodesy/azimuth_chain.hpp"

#include <cmath>

#include <fmt/format.h>

#include "meridian/core/angle.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/geodesy/laplace.hpp"

namespace meridian::geodesy {
namespace {

void require_finite(double v, const char* what) {
  if (!std::isfinite(v)) throw InputError(fmt::format("{} is not finite ({})", what, v));
}

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

// Inverse Laplace step: A = α − (−η·tan φ) = α + η·tan φ, σ_A = hypot(σ_α, σ_η·tan φ).
Uncertain astronomic_from_geodetic(Uncertain alpha, const AzimuthReduction& r, AzimuthSteps& s) {
  if (!r.eta_rad) return alpha;
  s.laplace_correction_rad = laplace_correction_rad(r.eta_rad->value, r.latitude_rad);
  s.laplace_applied = true;
  return {alpha.value - s.laplace_correction_rad,
          std::hypot(alpha.sigma, r.eta_rad->sigma * std::tan(r.latitude_rad))};
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
    alpha = wrap_positive_rad(a + s.laplace_correction_rad);
    salpha = std::hypot(sa, std::tan(r.latitude_rad) * r.eta_rad->sigma);
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
