#include "meridian/gravity/gravity_circle.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <thread>

#include <fmt/format.h>


#include "astronomic.hpp"
#include "not_finite.hpp"
#include "synthesis.hpp"

namespace meridian::gravity {
namespace {
using detail::kNaN;

// The values asked for are finite at node (i, j) of evaluate_parallels, or a NumericalError.
void check_node(const FieldValues& v, Quantities what, std::size_t i, std::size_t j) {
  const bool ok = (!includes(what, Quantities::Deflection) || (std::isfinite(v.xi_rad) && std::isfinite(v.eta_rad))) &&
                  (!includes(what, Quantities::Geoid) || std::isfinite(v.geoid_m));
  if (!ok) throw detail::model_value_not_finite(fmt::format("points[{}, {}]", i, j));
}

}  // namespace

// Column sums at the point's height (gradient) and, for the geoid, at h = 0.
struct GravityCircle::Impl {
  const GravityField* field = nullptr;
  Quantities what = Quantities::All;
  double t = 0, u = 0, q = 0, r = 0, gamma = 0;        // at the height
  EcefPosition gamma_at_lon0;                          // γ vector at λ = 0
  double t0 = 0, u0 = 0, q0 = 0, r0 = 0, gamma0 = 0;   // on the ellipsoid
  std::vector<double> sums, sums0, corr;
};

GravityCircle::GravityCircle(const GravityField& field, double lat_rad, double height_m, Quantities what)
    : impl_(std::make_unique<Impl>()), lat_rad_(lat_rad), height_m_(height_m) {
  GravityField::check_point({lat_rad, 0.0, height_m});
  Impl& s = *impl_;
  s.field = &field;
  s.what = what;
  const NormalGravity& normal = field.normal();
  auto spherical = [&](double h, double& t, double& u, double& q, double& r) {
    const EcefPosition e = normal.to_ecef(lat_rad, 0.0, h);  // λ = 0: x = p, y = 0
    r = std::hypot(e.x_m, e.z_m);
    t = e.z_m / r;
    u = e.x_m / r;
    q = field.model_radius_m() / r;
    return e;
  };
  if (includes(what, Quantities::Deflection)) {
    const EcefPosition e = spherical(height_m, s.t, s.u, s.q, s.r);
    s.gamma_at_lon0 = normal.gravity_vector_m_s2(e);  // |γ| does not depend on λ
    s.gamma = std::hypot(std::hypot(s.gamma_at_lon0.x_m, s.gamma_at_lon0.y_m), s.gamma_at_lon0.z_m);
    s.sums = field.disturbing_table().column_sums(s.t, s.q, true);
  }
  if (includes(what, Quantities::Geoid)) {
    spherical(0.0, s.t0, s.u0, s.q0, s.r0);
    s.gamma0 = normal.surface_gravity_m_s2(lat_rad);
    s.sums0 = field.disturbing_table().column_sums(s.t0, s.q0, false);
    if (field.correction_table()) s.corr = field.correction_table()->column_sums(s.t0, 1.0, false);
  }
}

GravityCircle::~GravityCircle() = default;
GravityCircle::GravityCircle(GravityCircle&&) noexcept = default;
GravityCircle& GravityCircle::operator=(GravityCircle&&) noexcept = default;

FieldValues GravityCircle::evaluate(double lon_rad) const {
  const Impl& s = *impl_;
  const GravityField& f = *s.field;
  FieldValues o{kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN};
  const double k = f.model_gm_m3_s2() / f.model_radius_m(), cl = std::cos(lon_rad), sl = std::sin(lon_rad);
  const double dgm = f.include_degree_zero() ? f.degree_zero_gm_m3_s2() : 0.0;
  if (includes(s.what, Quantities::Deflection)) {
    const detail::LaneSums v = f.disturbing_table().horner(s.sums, true, {s.t, s.u, s.q, cl, sl});
    const double t = k * v.v + dgm / s.r, dup = -k / s.r * v.dr - dgm / (s.r * s.r);
    o.disturbing_potential_m2_s2 = t;
    o.dT_up_m_s2 = dup;
    o.dT_north_m_s2 = k / s.r * v.dn;
    o.dT_east_m_s2 = k / s.r * v.de;
    o.anomaly_m_s2 = -dup - 2 * t / s.r;
    o.normal_gravity_m_s2 = s.gamma;
    o.xi_rad = -o.dT_north_m_s2 / s.gamma;
    o.eta_rad = -o.dT_east_m_s2 / s.gamma;
    // γ at λ: the λ = 0 vector rotated about the polar axis.
    const EcefPosition g{s.gamma_at_lon0.x_m * cl, s.gamma_at_lon0.x_m * sl, s.gamma_at_lon0.z_m};
    const double dup_all = f.include_degree_zero() ? dup : dup - f.degree_zero_gm_m3_s2() / (s.r * s.r);
    detail::astronomic_deflection(g, o.dT_east_m_s2, o.dT_north_m_s2, dup_all, s.t, s.u, lat_rad_, lon_rad, o.xi_astro_rad,
                                  o.eta_astro_rad);
  }
  if (includes(s.what, Quantities::Geoid)) {
    const detail::LaneSums v = f.disturbing_table().horner(s.sums0, false, {s.t0, s.u0, s.q0, cl, sl});
    double n = (k * v.v + dgm / s.r0) / s.gamma0;
    if (f.correction_table())
      n += f.correction_multiplier() * f.correction_table()->horner(s.corr, false, {s.t0, s.u0, 1.0, cl, sl}).v;
    o.geoid_m = n;
  }
  return o;
}

std::vector<FieldValues> GravityCircle::evaluate(std::span<const double> lon_rad) const {
  std::vector<FieldValues> out;
  out.reserve(lon_rad.size());
  for (double l : lon_rad) out.push_back(evaluate(l));
  return out;
}

void evaluate_parallels(const GravityField& field, std::span<const double> lat_rad, std::span<const double> lon_rad,
                        double height_m, Quantities what, unsigned threads, const ParallelSink& sink) {
  const std::size_t rows = lat_rad.size(), cols = lon_rad.size();
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto work = [&] {
    try {
      std::vector<FieldValues> values(cols);
      for (std::size_t i; (i = next.fetch_add(1)) < rows;) {
        const GravityCircle circle(field, lat_rad[i], height_m, what);
        for (std::size_t j = 0; j < cols; ++j) {
          values[j] = circle.evaluate(lon_rad[j]);
          check_node(values[j], what, i, j);
        }
        sink(i, values);
      }
    } catch (...) {
      next = rows;  // the others stop at their next row
      const std::lock_guard lock(failure_mutex);
      if (!failure) failure = std::current_exception();
    }
  };
  const unsigned wanted = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
  const std::size_t nthreads = std::min<std::size_t>(wanted, rows);
  {
    std::vector<std::jthread> pool;
    for (std::size_t t = 1; t < nthreads; ++t) pool.emplace_back(work);
    work();
  }
  if (failure) std::rethrow_exception(failure);
}

}  // namespace meridian::gravity
