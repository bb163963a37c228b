#include "meridian/gravity/gravity_field.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <thread>
#include <utility>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "astronomic.hpp"
#include "not_finite.hpp"
#include "synthesis.hpp"

namespace meridian::gravity {
namespace {

using detail::kNaN;

// The disturbing potential's coefficients are the model's minus the normal field's even zonal
// terms C̄_n0 = −(GM_ref/GM)(a_ref/a)^n J_n/√(2n+1), with C̄00 cancelled exactly (the GM
// difference is handled separately): applied to the table's own copy of the coefficients.
void remove_normal_field(detail::SynthesisTable& t, const GravityModelData& m, const NormalGravity& normal) {
  t.set_zonal_c(0, 0.0);
  const double amult = (normal.a_m() / m.radius_m) * (normal.a_m() / m.radius_m);
  double mult = normal.gm_m3_s2() / m.gm_m3_s2;
  for (int n = 2; n <= t.max_degree(); n += 2) {
    mult *= amult;
    const double s = -mult * normal.jn(n) / std::sqrt(2.0 * n + 1);
    if (s == 0) break;  // J_n underflowed: nothing left to remove
    t.set_zonal_c(n, t.zonal_c(n) - s);
  }
}

}  // namespace

GravityField::GravityField(const GravityModelData& model, FieldOptions options)
    : GravityField(model, model.coefficients, options) {}

GravityField::GravityField(GravityModelData&& model, FieldOptions options)
    : GravityField(model, std::move(model.coefficients), options) {
  model.coefficients = SphericalHarmonicCoefficients();  // a valid, empty (degree 0) set
}

// `model` supplies everything but the coefficients (which may have been moved out of it).
GravityField::GravityField(const GravityModelData& model, SphericalHarmonicCoefficients coefficients,
                           FieldOptions options)
    : normal_(model.reference),
      gm_(model.gm_m3_s2),
      radius_m_(model.radius_m),
      include_degree_zero_(options.include_degree_zero),
      threads_(options.threads) {
  if (!(std::isfinite(gm_) && gm_ > 0)) throw InputError("gravity model: GM must be positive", {model.source_file, {}, "gm"});
  if (!(std::isfinite(radius_m_) && radius_m_ > 0))
    throw InputError("gravity model: reference radius must be positive", {model.source_file, {}, "radius"});
  dgm_ = gm_ * coefficients.c(0, 0) - normal_.gm_m3_s2();
  const SimdKernel kernel = resolve_simd_kernel(options.simd_kernel);
  table_ = std::make_unique<detail::SynthesisTable>(std::move(coefficients), kernel);
  remove_normal_field(*table_, model, normal_);
  if (model.correction) {
    SphericalHarmonicCoefficients cc = model.correction->coefficients;
    if (!(model.correction->multiplier > 0))
      throw InputError("geoid correction multiplier must be positive", {model.source_file, {}, "CorrectionMultiplier"});
    cc.set(0, 0, cc.c(0, 0) + model.correction->height_offset_m / model.correction->multiplier, 0.0);
    corr_mult_ = model.correction->multiplier;
    correction_ = std::make_unique<detail::SynthesisTable>(std::move(cc), kernel);
  }
  if (threads_ == 0) threads_ = std::max(1u, std::thread::hardware_concurrency());
}

GravityField::~GravityField() = default;
GravityField::GravityField(GravityField&&) noexcept = default;
GravityField& GravityField::operator=(GravityField&&) noexcept = default;

int GravityField::max_degree() const noexcept { return table_->max_degree(); }
int GravityField::max_order() const noexcept { return table_->max_order(); }
SimdKernel GravityField::simd_kernel() const noexcept { return table_->kernel(); }

void GravityField::check_point(const GeodeticPoint& p) {
  if (!std::isfinite(p.lat_rad) || std::abs(p.lat_rad) > std::numbers::pi / 2)
    throw InputError(fmt::format("latitude {} deg is outside [-90, 90]", p.lat_rad * 180 / std::numbers::pi),
                     {"", {}, "lat"});
  if (!std::isfinite(p.lon_rad)) throw InputError("longitude is not a finite number", {"", {}, "lon"});
  if (!std::isfinite(p.height_m) || p.height_m < kMinHeight_m || p.height_m > kMaxHeight_m)
    throw InputError(fmt::format("height {} m is outside the model's range of validity [{}, {}] m", p.height_m,
                                 kMinHeight_m, kMaxHeight_m),
                     {"", {}, "h"});
}

void GravityField::evaluate_block(const GeodeticPoint* p, std::size_t count, Quantities what, FieldValues* out) const {
  const int n = static_cast<int>(count);
  detail::LanePoint lanes[detail::kPointsPerPass]{};
  detail::LaneSums sums[detail::kPointsPerPass]{};
  double r[detail::kPointsPerPass]{};
  EcefPosition ecef[detail::kPointsPerPass]{};
  bool all_on_ellipsoid = true;
  // Geocentric spherical variables of a geodetic point.
  auto lane = [&](int i, double h) {
    ecef[i] = normal_.to_ecef(p[i].lat_rad, p[i].lon_rad, h);
    const double pr = std::hypot(ecef[i].x_m, ecef[i].y_m);
    r[i] = std::hypot(pr, ecef[i].z_m);
    lanes[i] = {ecef[i].z_m / r[i], pr / r[i], radius_m_ / r[i], std::cos(p[i].lon_rad), std::sin(p[i].lon_rad)};
  };
  for (int i = 0; i < n; ++i) {
    out[i] = FieldValues{kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN};
    all_on_ellipsoid = all_on_ellipsoid && p[i].height_m == 0;
  }
  const double k = gm_ / radius_m_;
  if (includes(what, Quantities::Deflection)) {
    for (int i = 0; i < n; ++i) lane(i, p[i].height_m);
    table_->evaluate(lanes, n, true, sums);
    for (int i = 0; i < n; ++i) {
      FieldValues& o = out[i];
      double t = k * sums[i].v, dup = -k / r[i] * sums[i].dr;
      if (include_degree_zero_) {
        t += dgm_ / r[i];
        dup -= dgm_ / (r[i] * r[i]);
      }
      o.disturbing_potential_m2_s2 = t;
      o.dT_up_m_s2 = dup;
      o.dT_north_m_s2 = k / r[i] * sums[i].dn;
      o.dT_east_m_s2 = k / r[i] * sums[i].de;
      o.anomaly_m_s2 = -dup - 2 * t / r[i];
      const EcefPosition gv = normal_.gravity_vector_m_s2(ecef[i]);
      o.normal_gravity_m_s2 = std::hypot(std::hypot(gv.x_m, gv.y_m), gv.z_m);
      // The plumb line follows the whole g = ∇W: include the degree-0 term.
      const double dup_all = include_degree_zero_ ? dup : dup - dgm_ / (r[i] * r[i]);
      detail::astronomic_deflection(gv, o.dT_east_m_s2, o.dT_north_m_s2, dup_all, lanes[i].t, lanes[i].u, p[i].lat_rad,
                                    p[i].lon_rad, o.xi_astro_rad, o.eta_astro_rad);
      o.xi_rad = -o.dT_north_m_s2 / o.normal_gravity_m_s2;
      o.eta_rad = -o.dT_east_m_s2 / o.normal_gravity_m_s2;
    }
  }
  if (includes(what, Quantities::Geoid)) {
    const bool reuse = includes(what, Quantities::Deflection) && all_on_ellipsoid;
    if (!reuse) {
      for (int i = 0; i < n; ++i) lane(i, 0.0);
      table_->evaluate(lanes, n, false, sums);
    }
    detail::LaneSums corr[detail::kPointsPerPass]{};
    if (correction_) {
      detail::LanePoint unit[detail::kPointsPerPass]{};
      for (int i = 0; i < n; ++i) unit[i] = {lanes[i].t, lanes[i].u, 1.0, lanes[i].cos_lon, lanes[i].sin_lon};
      correction_->evaluate(unit, n, false, corr);
    }
    for (int i = 0; i < n; ++i) {
      double t = reuse ? out[i].disturbing_potential_m2_s2 : k * sums[i].v;
      if (!reuse && include_degree_zero_) t += dgm_ / r[i];
      out[i].geoid_m = t / normal_.surface_gravity_m_s2(p[i].lat_rad) + (correction_ ? corr_mult_ * corr[i].v : 0.0);
    }
  }
}

namespace {

// Values a model gives are finite or the evaluation is a NumericalError
// (coefficients, GM or radius out of range), never NaN in an output.
void check_finite_values(const FieldValues& v, Quantities what, std::size_t index) {
  const bool defl = includes(what, Quantities::Deflection),
             geoid = includes(what, Quantities::Geoid);
  const bool ok = (!defl || (std::isfinite(v.disturbing_potential_m2_s2) && std::isfinite(v.xi_rad) &&
                             std::isfinite(v.eta_rad) && std::isfinite(v.anomaly_m_s2) && std::isfinite(v.dT_east_m_s2) &&
                             std::isfinite(v.dT_north_m_s2) && std::isfinite(v.dT_up_m_s2) &&
                             std::isfinite(v.xi_astro_rad) && std::isfinite(v.eta_astro_rad))) &&
                  (!geoid || std::isfinite(v.geoid_m));
  if (!ok) throw detail::model_value_not_finite(fmt::format("points[{}]", index));
}

}  // namespace

FieldValues GravityField::evaluate(const GeodeticPoint& p, Quantities what) const {
  check_point(p);
  FieldValues v;
  evaluate_block(&p, 1, what, &v);
  check_finite_values(v, what, 0);
  return v;
}

std::vector<FieldValues> GravityField::evaluate(std::span<const GeodeticPoint> points, Quantities what) const {
  for (std::size_t i = 0; i < points.size(); ++i) {
    try {
      check_point(points[i]);
    } catch (Error& e) {
      e.add_context("", std::nullopt, fmt::format("points[{}]", i));
      throw;
    }
  }
  std::vector<FieldValues> out(points.size());
  // Passes of kPointsPerPass points, smaller (down to one vector) when that gives every thread one.
  const std::size_t per_thread = (points.size() + threads_ - 1) / threads_;  // threads_ ≥ 1
  const std::size_t lanes = std::clamp<std::size_t>(per_thread, detail::kLanes, detail::kPointsPerPass);
  const std::size_t blocks = (points.size() + lanes - 1) / lanes;
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t b; (b = next.fetch_add(1)) < blocks;) {
      const std::size_t i0 = b * lanes;
      evaluate_block(points.data() + i0, std::min(lanes, points.size() - i0), what, out.data() + i0);
    }
  };
  const std::size_t nthreads = std::min<std::size_t>(threads_, blocks);
  if (nthreads <= 1) {
    work();
  } else {
    std::vector<std::jthread> pool;
    for (std::size_t i = 1; i < nthreads; ++i) pool.emplace_back(work);
    work();
  }
  for (std::size_t i = 0; i < out.size(); ++i) check_finite_values(out[i], what, i);
  return out;
}

}  // namespace meridian::gravity
