#include "meridian/gyro/instrument.hpp"

#include <cmath>

#include "meridian/core/angle.hpp"

namespace meridian::gyro {
namespace {

// −λ·τ·α_p and its σ (independent λ, τ, α_p).
Uncertain zero_correction(const Instrument& inst, const ZeroPosition& zero) {
  if (!zero) return {};
  const double lam = inst.torsion_ratio.value;
  const double tau = inst.scale_value_rad;
  const double ap = zero->value;
  const double var = std::pow(lam * tau * zero->sigma, 2) +
                     std::pow(tau * ap * inst.torsion_ratio.sigma, 2) +
                     std::pow(lam * ap * inst.sigma_scale_value_rad, 2);
  return {-lam * tau * ap, std::sqrt(var)};
}

}  // namespace

NorthReading north_from_nontracking(double clamp_rad, Uncertain beta, const Instrument& inst,
                                    const ZeroPosition& zero) {
  const double lam = inst.torsion_ratio.value;
  const double tau = inst.scale_value_rad;
  const double ap = zero ? zero->value : 0.0;
  // N_G = N' + (1+λ)τβ − λτα_p; partials: ∂/∂β = (1+λ)τ, ∂/∂λ = τ(β − α_p),
  // ∂/∂τ = (1+λ)β − λα_p, ∂/∂α_p = −λτ.
  NorthReading r;
  const Uncertain zc = zero_correction(inst, zero);
  r.zero_correction_rad = zc.value;
  r.sigma_zero_correction_rad = zc.sigma;
  r.delta_n_rad = (1.0 + lam) * tau * beta.value + zc.value;
  double var = std::pow((1.0 + lam) * tau * beta.sigma, 2) +
               std::pow(tau * (beta.value - ap) * inst.torsion_ratio.sigma, 2) +
               std::pow(((1.0 + lam) * beta.value - lam * ap) * inst.sigma_scale_value_rad, 2);
  if (zero) var += std::pow(lam * tau * zero->sigma, 2);
  r.sigma_rad = std::sqrt(var);
  r.north_rad = wrap_positive_rad(clamp_rad + r.delta_n_rad);
  return r;
}

NorthReading north_from_delta(double clamp_rad, Uncertain delta_n, const Instrument& inst,
                              const ZeroPosition& zero) {
  NorthReading r;
  const Uncertain zc = zero_correction(inst, zero);
  r.zero_correction_rad = zc.value;
  r.sigma_zero_correction_rad = zc.sigma;
  r.delta_n_rad = delta_n.value + zc.value;
  r.sigma_rad = std::hypot(delta_n.sigma, zc.sigma);
  r.north_rad = wrap_positive_rad(clamp_rad + r.delta_n_rad);
  return r;
}

NorthReading north_from_tracking(Uncertain centre, const Instrument& inst, const ZeroPosition& zero) {
  NorthReading r;
  const Uncertain zc = zero_correction(inst, zero);
  r.zero_correction_rad = zc.value;
  r.sigma_zero_correction_rad = zc.sigma;
  r.delta_n_rad = zc.value;
  r.sigma_rad = std::hypot(centre.sigma, zc.sigma);
  r.north_rad = wrap_positive_rad(centre.value + zc.value);
  return r;
}

}  // namespace meridian::gyro
