// Grid synthesis (issue 14): per parallel, the order-m column sums of the stable recursion
// (synthesis.hpp, the same sums GravityCircle uses), then either one real inverse FFT per
// quantity (longitude spacing dividing 360°) or GravityCircle's O(M) Horner pass per node.
// The FFT path sums blocks of up to 16 parallels in one pass over the coefficients, in the
// SIMD kernel (the sums are its O(N²) part: scalar, one parallel at a time, they took at least 94 % of
// a degree-2190 global grid). docs/gravity-field.md,
// "Grids", has the formulas.
//
// The FFT path. The point path combines the column sums (scaled by 1e-280 and divided by u^m)
// by Horner's rule in z = u q e^{iλ}; here each order's term is written out as a Fourier
// coefficient instead. With F_m = (u q)^m · 1e280 and F'_m = (u q)^{m−1} · 1e280 (kept as
// mantissa and binary exponent, so neither under- nor overflows on the way; only the final
// product is rounded), the real functions of λ on the parallel are Re Σm c_m e^{imλ} with
//   v : c_m = q F_m (A0 − i B0)                              (T = K v, K = GM/a)
//   dr: c_m = q F_m (A1 − i B1)                              (∂T/∂r = −(K/r) dr)
//   dn: c_m = q u F_m (A2 − i B2) − q² t m F'_m (A0 − i B0)  ((1/r) ∂T/∂ψ = (K/r) dn)
//   de: c_m = q² m F'_m (B0 + i A0)                          ((1/(r cos ψ)) ∂T/∂λ = (K/r) de)
// (the same terms as SynthesisTable::horner, t = sin ψ, u = cos ψ, q = a/r). Each output
// quantity is a linear combination of these plus a constant (the degree-0 term). At the nodes
// λ_k = λ0 + 2πk/Nλ, e^{imλ_k} = e^{imλ0} ω^{(m mod Nλ)k}, ω = e^{2πi/Nλ}: the coefficients,
// shifted by e^{imλ0}, are summed into bins m mod Nλ (C_j), and f_k = Re Σj C_j ω^{jk} =
// Σj X_j ω^{jk} with the Hermitian X_j = (C_j + conj C_{(Nλ−j) mod Nλ})/2, j = 0 … Nλ/2:
// exactly FFTW's unnormalised c2r transform. Orders above Nλ/2 are thus folded, not lost.

#include "meridian/gravity/grid_synthesis.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <complex>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include <fftw3.h>
#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/gravity/gravity_circle.hpp"
#include "synthesis.hpp"

namespace meridian::gravity {
namespace {

using Complex = std::complex<double>;

// FFTW's planner (plan creation and destruction) is not thread-safe; execution of a plan with
// the new-array interface is. The one process-wide lock that guards it.
std::mutex& fftw_planner_mutex() {
  static std::mutex m;
  return m;
}

// x · 2^exp with x in [0.5, 1) (or 0): a power of u q times 1e280 without under- or overflow.
struct ScaledPower {
  double mantissa;
  int exponent;
  static ScaledPower scale() {
    int e = 0;
    const double m = std::frexp(detail::kInvScale, &e);
    return {m, e};
  }
  void multiply(double x) {
    int e = 0;
    mantissa = std::frexp(mantissa * x, &e);
    exponent += e;
  }
  // a · (this power); a is a column sum (scaled by 1e-280).
  double operator()(double a) const { return std::ldexp(a * mantissa, exponent); }
};

// The geometry of one parallel at one height: spherical coordinates of the point at λ = 0.
struct Parallel {
  double t = 0, u = 0, q = 0, r = 0;
};

Parallel parallel_at(const GravityField& field, double lat_rad, double height_m, EcefPosition* ecef = nullptr) {
  const EcefPosition e = field.normal().to_ecef(lat_rad, 0.0, height_m);  // λ = 0: x = p, y = 0
  if (ecef) *ecef = e;
  Parallel p;
  p.r = std::hypot(e.x_m, e.z_m);
  p.t = e.z_m / p.r;
  p.u = e.x_m / p.r;
  p.q = field.model_radius_m() / p.r;
  return p;
}

bool needs_gradient(const std::vector<GridQuantity>& q) {
  return std::any_of(q.begin(), q.end(), [](GridQuantity x) { return x != GridQuantity::Geoid; });
}
bool needs_geoid(const std::vector<GridQuantity>& q) {
  return std::find(q.begin(), q.end(), GridQuantity::Geoid) != q.end();
}

double pick(const FieldValues& v, GridQuantity q) {
  switch (q) {
    case GridQuantity::Xi: return v.xi_rad;
    case GridQuantity::Eta: return v.eta_rad;
    case GridQuantity::Geoid: return v.geoid_m;
    case GridQuantity::Anomaly: return v.anomaly_m_s2;
    case GridQuantity::DisturbanceEast: return v.dT_east_m_s2;
    case GridQuantity::DisturbanceNorth: return v.dT_north_m_s2;
    case GridQuantity::DisturbanceUp: return v.dT_up_m_s2;
  }
  return detail::kNaN;
}

// The plan of one c2r transform of length n, made and destroyed under the planner lock.
class C2rPlan {
 public:
  explicit C2rPlan(int n) : n_(n) {
    std::lock_guard lock(fftw_planner_mutex());
    fftw_complex* in = fftw_alloc_complex(static_cast<std::size_t>(n / 2 + 1));
    double* out = fftw_alloc_real(static_cast<std::size_t>(n));
    if (in && out) plan_ = fftw_plan_dft_c2r_1d(n, in, out, FFTW_ESTIMATE);
    fftw_free(in);
    fftw_free(out);
    if (!plan_) throw NumericalError(fmt::format("FFTW could not plan a real transform of length {}", n));
  }
  ~C2rPlan() {
    std::lock_guard lock(fftw_planner_mutex());
    fftw_destroy_plan(plan_);
  }
  C2rPlan(const C2rPlan&) = delete;
  C2rPlan& operator=(const C2rPlan&) = delete;
  int size() const { return n_; }
  // in: n/2 + 1 values (destroyed), out: n values; both from fftw_alloc_* (same alignment).
  void execute(fftw_complex* in, double* out) const { fftw_execute_dft_c2r(plan_, in, out); }

 private:
  int n_;
  fftw_plan plan_ = nullptr;
};

// What one thread of the FFT path owns.
class FftWorker {
 public:
  explicit FftWorker(std::size_t n)
      : in_(fftw_alloc_complex(n / 2 + 1)), out_(fftw_alloc_real(n)), bins_(n) {
    if (!in_ || !out_) {
      release();
      throw std::bad_alloc();
    }
  }
  ~FftWorker() { release(); }
  FftWorker(const FftWorker&) = delete;
  FftWorker& operator=(const FftWorker&) = delete;

  // The column sums of the current block of parallels (SynthesisTable::column_sums).
  std::vector<double> sums[detail::kBlockParallels], sums0[detail::kBlockParallels],
      sums_corr[detail::kBlockParallels];
  // The coefficient sets of the current parallel (length max order + 1 or empty).
  std::vector<Complex> v, dr, dn, de, v0, corr, combined;

  // Sample Re Σm c_m e^{imλ} at λ0 + 2πk/n, k = 0 … n−1 (phase[m] = e^{imλ0}); returns the n values.
  const double* sample(const C2rPlan& plan, const std::vector<Complex>& c, const std::vector<Complex>& phase) {
    const std::size_t n = bins_.size();
    std::fill(bins_.begin(), bins_.end(), Complex{});
    for (std::size_t m = 0; m < c.size(); ++m) bins_[m % n] += c[m] * phase[m];
    for (std::size_t j = 0; j <= n / 2; ++j) {
      const Complex x = 0.5 * (bins_[j] + std::conj(bins_[(n - j) % n]));
      in_[j][0] = x.real();
      in_[j][1] = x.imag();
    }
    plan.execute(in_, out_);
    return out_;
  }

 private:
  void release() {
    fftw_free(in_);
    fftw_free(out_);
  }
  fftw_complex* in_;
  double* out_;
  std::vector<Complex> bins_;
};

// The shared, read-only state of one synthesis.
struct Job {
  const GravityField& field;
  const GridSpec& spec;
  std::size_t columns = 0;
  GridPath path = GridPath::Parallel;
  const C2rPlan* plan = nullptr;
  std::vector<Complex> phase;  // e^{imλ0}, m = 0 … max order (FFT path)
};

// c_m of v (and of dr, dn, de when `gradient`) from the column sums at one (t, u, q).
void fourier_coefficients(const std::vector<double>& sums, bool gradient, const Parallel& p, FftWorker& w,
                          std::vector<Complex>& v) {
  const std::size_t width = gradient ? 6 : 2, orders = sums.size() / width;
  v.assign(orders, Complex{});
  if (gradient) {
    w.dr.assign(orders, Complex{});
    w.dn.assign(orders, Complex{});
    w.de.assign(orders, Complex{});
  }
  ScaledPower f = ScaledPower::scale(), f_prev = f;  // F_m and F_{m−1}
  const double uq = p.u * p.q, q2 = p.q * p.q;
  for (std::size_t m = 0; m < orders; ++m) {
    const double* s = sums.data() + width * m;
    v[m] = p.q * Complex(f(s[0]), -f(s[1]));
    if (gradient) {
      w.dr[m] = p.q * Complex(f(s[2]), -f(s[3]));
      w.dn[m] = p.q * p.u * Complex(f(s[4]), -f(s[5]));
      if (m >= 1) {
        const double mm = static_cast<double>(m);
        const Complex g(f_prev(s[0]), -f_prev(s[1]));  // F'_m (A0 − i B0)
        w.dn[m] -= q2 * p.t * mm * g;
        w.de[m] = q2 * mm * Complex(-g.imag(), g.real());  // i · g = B0 + i A0 (times F'_m)
      }
    }
    f_prev = f;
    f.multiply(uq);
  }
}

// combined = a·x + b·y (y may be empty), plus `constant` in the m = 0 term.
void combine(std::vector<Complex>& out, double a, const std::vector<Complex>& x, double b,
             const std::vector<Complex>& y, double constant) {
  out.assign(std::max(x.size(), y.size()), Complex{});
  for (std::size_t m = 0; m < x.size(); ++m) out[m] += a * x[m];
  for (std::size_t m = 0; m < y.size(); ++m) out[m] += b * y[m];
  if (!out.empty()) out[0] += constant;
}

// One block of up to kBlockParallels consecutive rows (first … first + count − 1) by the FFT
// path: the column sums of the whole block in one pass over the coefficient table, then per row
// the Fourier coefficients and one c2r transform per quantity. out: count rows of per-row values.
void block_fft(const Job& job, std::size_t first, std::size_t count, FftWorker& w, double* out) {
  const GravityField& f = job.field;
  const GridSpec& spec = job.spec;
  const double k = f.model_gm_m3_s2() / f.model_radius_m();
  const double dgm = f.include_degree_zero() ? f.degree_zero_gm_m3_s2() : 0.0;
  const bool gradient = needs_gradient(spec.quantities), geoid = needs_geoid(spec.quantities);
  const detail::SynthesisTable* correction = f.correction_table();
  const int n_rows = static_cast<int>(count);
  Parallel p[detail::kBlockParallels], p0[detail::kBlockParallels];
  double r[detail::kBlockParallels]{}, gamma[detail::kBlockParallels]{}, gamma0[detail::kBlockParallels]{};
  double t[detail::kBlockParallels], q[detail::kBlockParallels], t0[detail::kBlockParallels],
      q0[detail::kBlockParallels], ones[detail::kBlockParallels];
  for (int i = 0; i < n_rows; ++i) {
    const double lat = spec.lat_rad(first + static_cast<std::size_t>(i));
    if (gradient) {
      EcefPosition e;
      p[i] = parallel_at(f, lat, spec.height_m, &e);
      const EcefPosition g = f.normal().gravity_vector_m_s2(e);
      r[i] = p[i].r;
      gamma[i] = std::hypot(std::hypot(g.x_m, g.y_m), g.z_m);
      t[i] = p[i].t;
      q[i] = p[i].q;
    }
    if (geoid) {
      p0[i] = parallel_at(f, lat, 0.0);
      gamma0[i] = f.normal().surface_gravity_m_s2(lat);
      t0[i] = p0[i].t;
      q0[i] = p0[i].q;
      ones[i] = 1.0;
    }
  }
  if (gradient) f.disturbing_table().column_sums(t, q, n_rows, true, w.sums);
  if (geoid) {
    f.disturbing_table().column_sums(t0, q0, n_rows, false, w.sums0);
    if (correction) correction->column_sums(t0, ones, n_rows, false, w.sums_corr);  // on the unit sphere
  }

  const std::size_t cols = job.columns, n = static_cast<std::size_t>(job.plan->size());
  const std::vector<Complex> none;
  for (int i = 0; i < n_rows; ++i) {
    if (gradient) fourier_coefficients(w.sums[i], true, p[i], w, w.v);
    if (geoid) {
      fourier_coefficients(w.sums0[i], false, p0[i], w, w.v0);
      w.corr.clear();
      if (correction) {
        Parallel unit = p0[i];
        unit.q = 1.0;
        fourier_coefficients(w.sums_corr[i], false, unit, w, w.corr);
      }
    }
    const double ri = r[i], r0 = p0[i].r;
    double* row_out = out + static_cast<std::size_t>(i) * cols * spec.quantities.size();
    for (std::size_t qi = 0; qi < spec.quantities.size(); ++qi) {
      switch (spec.quantities[qi]) {
        case GridQuantity::Xi: combine(w.combined, -k / (ri * gamma[i]), w.dn, 0, none, 0); break;
        case GridQuantity::Eta: combine(w.combined, -k / (ri * gamma[i]), w.de, 0, none, 0); break;
        case GridQuantity::DisturbanceNorth: combine(w.combined, k / ri, w.dn, 0, none, 0); break;
        case GridQuantity::DisturbanceEast: combine(w.combined, k / ri, w.de, 0, none, 0); break;
        case GridQuantity::DisturbanceUp: combine(w.combined, -k / ri, w.dr, 0, none, -dgm / (ri * ri)); break;
        // Δg = −∂T/∂r − 2T/r = (K/r)(dr − 2v) − dgm/r²
        case GridQuantity::Anomaly: combine(w.combined, k / ri, w.dr, -2 * k / ri, w.v, -dgm / (ri * ri)); break;
        case GridQuantity::Geoid:
          combine(w.combined, k / gamma0[i], w.v0, f.correction_multiplier(), w.corr, dgm / (r0 * gamma0[i]));
          break;
      }
      // Node i is sample i of the parallel from the grid's first longitude on: a regional grid
      // keeps its first columns, a global gridline grid's last column (E = W + 360°) is sample 0.
      const double* samples = w.sample(*job.plan, w.combined, job.phase);
      double* row = row_out + qi * cols;
      for (std::size_t c = 0; c < cols; ++c) row[c] = samples[c % n];
    }
  }
}

void row_parallel(const Job& job, std::size_t j, double* out) {
  const GridSpec& spec = job.spec;
  const Quantities what = static_cast<Quantities>(
      (needs_gradient(spec.quantities) ? static_cast<unsigned>(Quantities::Deflection) : 0u) |
      (needs_geoid(spec.quantities) ? static_cast<unsigned>(Quantities::Geoid) : 0u));
  const GravityCircle circle(job.field, spec.lat_rad(j), spec.height_m, what);
  for (std::size_t i = 0; i < job.columns; ++i) {
    const FieldValues v = circle.evaluate(spec.lon_rad(i));
    for (std::size_t qi = 0; qi < spec.quantities.size(); ++qi) out[qi * job.columns + i] = pick(v, spec.quantities[qi]);
  }
}

void check_finite(const GridSpec& spec, std::size_t j, const double* row, std::size_t columns) {
  for (std::size_t qi = 0; qi < spec.quantities.size(); ++qi)
    for (std::size_t i = 0; i < columns; ++i)
      if (!std::isfinite(row[qi * columns + i]))
        throw NumericalError(fmt::format("{} is not finite at lat {} deg, lon {} deg (damaged model?)",
                                         to_string(spec.quantities[qi]), spec.lat_deg(j), spec.lon_deg(i)),
                             {"", {}, fmt::format("rows[{}]", j)});
}

// Per-node heights: parallels in order on the calling thread, each node a scattered point
// (GravityField::evaluate, which spreads a parallel's nodes over the field's threads).
GridSynthesisResult synthesize_with_heights(const GravityField& field, const GridSpec& spec, const GridRowSink& sink,
                                            Progress* progress) {
  const std::size_t rows = spec.rows(), cols = spec.columns(), nq = spec.quantities.size();
  const Quantities what = static_cast<Quantities>(
      (needs_gradient(spec.quantities) ? static_cast<unsigned>(Quantities::Deflection) : 0u) |
      (needs_geoid(spec.quantities) ? static_cast<unsigned>(Quantities::Geoid) : 0u));
  std::vector<double> heights(cols), buffer(cols * nq);
  std::vector<GeodeticPoint> points(cols);
  report_progress(progress, 0, rows, "parallels");
  for (std::size_t j = 0; j < rows; ++j) {
    std::fill(heights.begin(), heights.end(), std::numeric_limits<double>::quiet_NaN());
    spec.node_heights(j, heights);
    for (std::size_t i = 0; i < cols; ++i) points[i] = {spec.lat_rad(j), spec.lon_rad(i), heights[i]};
    std::vector<FieldValues> v;
    try {
      v = field.evaluate(points, what);
    } catch (Error& e) {
      e.add_context("", std::nullopt, fmt::format("rows[{}]", j));
      throw;
    }
    for (std::size_t qi = 0; qi < nq; ++qi)
      for (std::size_t i = 0; i < cols; ++i) buffer[qi * cols + i] = pick(v[i], spec.quantities[qi]);
    check_finite(spec, j, buffer.data(), cols);
    sink(GridRow{j, spec.lat_deg(j), cols, buffer});
    report_progress(progress, j + 1, rows, "parallels");
  }
  GridSynthesisResult r;
  r.path_used = GridPath::Parallel;
  r.rows = rows;
  r.columns = cols;
  r.threads = 1;
  r.per_node_heights = true;
  return r;
}

std::size_t row_bytes(const GridSpec& spec) { return spec.columns() * spec.quantities.size() * sizeof(double); }

// What the FFT path shares between rows: one c2r plan of length Nλ (job.plan), the phases
// e^{imλ0} of the grid's first longitude (job.phase) and one worker per thread.
std::unique_ptr<C2rPlan> prepare_fft(Job& job, std::vector<std::unique_ptr<FftWorker>>& workers) {
  const std::size_t n = job.spec.samples_per_turn();
  auto plan = std::make_unique<C2rPlan>(static_cast<int>(n));
  job.plan = plan.get();
  int orders = job.field.max_order() + 1;
  if (const detail::SynthesisTable* c = job.field.correction_table()) orders = std::max(orders, c->max_order() + 1);
  const double lon0 = job.spec.lon_rad(0);
  job.phase.resize(static_cast<std::size_t>(orders));
  for (int m = 0; m < orders; ++m) job.phase[static_cast<std::size_t>(m)] = std::polar(1.0, m * lon0);
  for (auto& w : workers) w = std::make_unique<FftWorker>(n);
  return plan;
}

// Rows [first, first + count) into `out` (per_row values each), spread over the threads:
// blocks of consecutive rows, at most kBlockParallels (FFT path) and small enough that every
// thread gets one; one row each on the per-parallel path. Every value is checked finite. The
// first error of any thread stops the others and is rethrown.
void compute_rows(const Job& job, std::size_t first, std::size_t count, unsigned threads,
                  const std::vector<std::unique_ptr<FftWorker>>& workers, double* out_rows) {
  const std::size_t per_row = job.columns * job.spec.quantities.size();
  const std::size_t block =
      job.path == GridPath::Fft ? std::clamp<std::size_t>((count + threads - 1) / threads, 1, detail::kBlockParallels)
                                : 1;
  const std::size_t items = (count + block - 1) / block;
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::vector<std::exception_ptr> errors(threads);
  auto work = [&](unsigned t) {
    try {
      for (std::size_t k; !failed.load(std::memory_order_relaxed) && (k = next.fetch_add(1)) < items;) {
        const std::size_t k0 = k * block, n_rows = std::min(block, count - k0);
        double* out = out_rows + k0 * per_row;
        if (job.path == GridPath::Fft)
          block_fft(job, first + k0, n_rows, *workers[t], out);
        else
          row_parallel(job, first + k0, out);
        for (std::size_t i = 0; i < n_rows; ++i) check_finite(job.spec, first + k0 + i, out + i * per_row, job.columns);
      }
    } catch (...) {
      errors[t] = std::current_exception();
      failed = true;
    }
  };
  const unsigned active = static_cast<unsigned>(std::min<std::size_t>(threads, items));
  if (active <= 1) {
    work(0);
  } else {
    std::vector<std::jthread> pool;
    pool.reserve(active);
    for (unsigned t = 0; t < active; ++t) pool.emplace_back(work, t);
  }
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace

std::string_view to_string(GridPath p) noexcept {
  switch (p) {
    case GridPath::Auto: return "auto";
    case GridPath::Fft: return "fft";
    case GridPath::Parallel: return "parallel";
  }
  return "?";
}

GridPath grid_path_from_string(std::string_view name) {
  for (GridPath p : {GridPath::Auto, GridPath::Fft, GridPath::Parallel})
    if (name == to_string(p)) return p;
  throw InputError(fmt::format("unknown grid path \"{}\" (auto, fft or parallel)", std::string(name)),
                   {"", {}, "path"});
}

GridPath choose_grid_path(const GridSpec& spec, const GridOptions& options, int max_order) {
  spec.validate();
  if (row_bytes(spec) > options.max_buffer_bytes)
    throw InputError(fmt::format("one parallel of {} nodes × {} quantities needs {} bytes, more than the buffer "
                                 "limit of {} bytes",
                                 spec.columns(), spec.quantities.size(), row_bytes(spec), options.max_buffer_bytes),
                     {"", {}, "spacing"});
  const std::size_t n = spec.samples_per_turn();
  if (options.path == GridPath::Fft && n == 0)
    throw InputError(fmt::format("the FFT path needs a longitude spacing that divides 360° ({}° does not)",
                                 spec.lon_spacing_deg),
                     {"", {}, "path"});
  if (options.path == GridPath::Fft && spec.node_heights)
    throw InputError("the FFT path needs one height for the whole grid; per-node heights use the per-parallel path",
                     {"", {}, "path"});
  if (options.path != GridPath::Auto) return options.path;
  if (n == 0 || spec.node_heights) return GridPath::Parallel;
  if (spec.global_longitude()) return GridPath::Fft;
  const double per_parallel = static_cast<double>(spec.columns()) * (std::max(max_order, 0) + 1.0);
  const double fft = 2.0 * static_cast<double>(spec.quantities.size()) * static_cast<double>(n);
  return per_parallel >= fft ? GridPath::Fft : GridPath::Parallel;
}

GridSynthesisResult synthesize_grid(const GravityField& field, const GridSpec& spec, const GridRowSink& sink,
                                    Progress* progress, const GridOptions& options) {
  Job job{field, spec, 0, GridPath::Parallel, nullptr, {}};
  job.path = choose_grid_path(spec, options, field.max_order());
  if (spec.node_heights) return synthesize_with_heights(field, spec, sink, progress);
  job.columns = spec.columns();
  const std::size_t rows = spec.rows(), nq = spec.quantities.size(), per_row = job.columns * nq;
  unsigned threads = options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, rows));
  // Rows in flight: within the memory bound, enough to keep every thread busy between sinks.
  const std::size_t by_memory = std::max<std::size_t>(1, options.max_buffer_bytes / row_bytes(spec));
  // The FFT path works in blocks of parallels that share one pass over the coefficients
  // (SynthesisTable::column_sums); a batch holds two blocks per thread.
  const std::size_t per_thread = job.path == GridPath::Fft ? 2 * detail::kBlockParallels : 16;
  const std::size_t batch = std::min({rows, by_memory, per_thread * threads});

  GridSynthesisResult result;
  result.path_used = job.path;
  result.rows = rows;
  result.columns = job.columns;
  result.threads = threads;

  std::unique_ptr<C2rPlan> plan;
  std::vector<std::unique_ptr<FftWorker>> workers(threads);
  if (job.path == GridPath::Fft) {
    plan = prepare_fft(job, workers);
    result.fft_length = spec.samples_per_turn();
  }

  std::vector<double> buffer(batch * per_row);
  report_progress(progress, 0, rows, "parallels");
  for (std::size_t first = 0; first < rows; first += batch) {
    const std::size_t count = std::min(batch, rows - first);
    compute_rows(job, first, count, threads, workers, buffer.data());
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t j = first + k;
      sink(GridRow{j, spec.lat_deg(j), job.columns, std::span<const double>(buffer.data() + k * per_row, per_row)});
    }
    report_progress(progress, first + count, rows, "parallels");
  }
  return result;
}

}  // namespace meridian::gravity
