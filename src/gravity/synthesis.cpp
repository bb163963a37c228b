// The summation kernel. Compiled with -ffp-contract=fast and once per instruction set
// (gravity/simd_kernel.hpp: baseline, AVX2 + FMA, AVX-512), chosen at run time, so one binary
// runs everywhere at full speed.
//
// For each order m (descending) and each of kLanes points at once, the
// forward column recursion over n of W_n = q^{n−m} P̄_nm(t)/u^m · kScale:
//   W_n = α_nm t q W_{n−1} − β_nm q² W_{n−2},   W_m = kScale · P̄_mm/u^m,
// accumulates A0 = Σ C W, B0 = Σ S W, K = Σ (n−m) C W, L = Σ (n−m) S W, and for the
// t-derivative D_n = ∂W_n/∂t (A2 = Σ C D, B2 = Σ S D) one of two forms:
//  * away from the poles, the derivative identity of the associated Legendre functions,
//    (1 − t²) dP̄_nm/dt = −n t P̄_nm + f_nm P̄_{n−1,m}, f_nm = √((2n+1)(n²−m²)/(2n−1)), which for
//    W reads u² D_n = f_nm q W_{n−1} − (n−m) t W_n: two sums F = Σ f C W_{n−1}, G = Σ f S W_{n−1}
//    and A2 = (q F − t K)/u² per order — two multiply-adds per term instead of a second recursion;
//  * near the poles (u < kIdentityMinCos, lane by lane), where 1/u² would amplify the rounding,
//    the recursion D_n = α_nm q (W_{n−1} + t D_{n−1}) − β_nm q² D_{n−2}.
// A1 = Σ (n+1) C W = K + (m+1) A0. The orders are then combined by Horner's rule in
// z = u q e^{iλ}, which restores the u^m q^m factors without ever forming them (no underflow).

#include "synthesis.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace meridian::gravity::detail {

SynthesisTable::SynthesisTable(SphericalHarmonicCoefficients c, SimdKernel kernel)
    : n_(c.max_degree()), m_(c.max_order()), kernel_(resolve_simd_kernel(kernel)), coefficients_(std::move(c)) {
  // α_nm = √((2n−1)(2n+1) / ((n−m)(n+m))), β_nm = √((2n+1)(n+m−1)(n−m−1) / ((n−m)(n+m)(2n−3)))
  // are formed in the kernel from these tables (products instead of a square root and a
  // division per term; a few ulp from the direct forms).
  const std::size_t roots = 2 * static_cast<std::size_t>(n_) + 2, degrees = static_cast<std::size_t>(n_) + 1;
  roots_.root.resize(roots);
  roots_.inv_root.resize(roots);
  for (std::size_t k = 0; k < roots; ++k) {
    roots_.root[k] = std::sqrt(static_cast<double>(k));
    roots_.inv_root[k] = k == 0 ? 0.0 : 1.0 / roots_.root[k];
  }
  roots_.r2p1.assign(degrees, 0.0);
  roots_.r2m1.assign(degrees, 0.0);
  roots_.inv_r2m1.assign(degrees, 0.0);
  roots_.inv_r2m3.assign(degrees, 0.0);
  for (std::size_t n = 0; n < degrees; ++n) {
    roots_.r2p1[n] = roots_.root[2 * n + 1];
    if (n >= 1) roots_.r2m1[n] = roots_.root[2 * n - 1];
    if (n >= 1) roots_.inv_r2m1[n] = roots_.inv_root[2 * n - 1];
    if (n >= 2) roots_.inv_r2m3[n] = roots_.inv_root[2 * n - 3];
  }
  start_.resize(static_cast<std::size_t>(m_) + 1);
  sectoral_.resize(static_cast<std::size_t>(m_) + 1);
  for (int m = 0; m <= m_; ++m) {
    start_[static_cast<std::size_t>(m)] = coefficients_.index(m, m);
    double p = kScale;
    if (m == 1) p = kScale * std::sqrt(3.0);
    if (m >= 2) p = sectoral_[static_cast<std::size_t>(m) - 1] * std::sqrt((2.0 * m + 1) / (2.0 * m));
    sectoral_[static_cast<std::size_t>(m)] = p;
  }
}

namespace {

typedef double V8 __attribute__((vector_size(kLanes * sizeof(double))));
typedef double V4 __attribute__((vector_size(4 * sizeof(double))));

#define MERIDIAN_INLINE inline __attribute__((always_inline))

// How a group of lanes forms the t-derivative sums (top of this file): not at all (values
// only), by the derivative identity, by the derivative's own recursion (every lane near a
// pole), or both (a group with lanes of each kind; each lane then takes its own form, so that
// a point's result never depends on the points it shares a group with).
enum class Deriv { None, Identity, Recursion, Both };

// Lanes with u = cos ψ at least this use the identity, whose rounding could grow as 1/u²;
// nearer the poles (|ψ| > 84.26°), the recursion. Against a long-double evaluation of a random
// degree-2190 model, the north derivative's largest error was 0.5–1.0e-13 of its largest value
// at 80°–84.2° by the identity and 0.4–1.2e-13 by the recursion (2e-14 and 1e-14 at 75°);
// tests: GravityClosedForm.NorthDerivativeAcrossTheChangeOfForm.
inline constexpr double kIdentityMinCos = 0.1;

// The forward recursion of one column for one group of lanes, resumable: W_{k−1}, W_{k−2},
// D_{k−1}, D_{k−2} (Recursion, Both) and the sums after term k − 1: A0, B0, K, L, then F, G
// (Identity, Both) and A2, B2 (Recursion, Both).
template <class V>
struct ColumnState {
  V w1, w2, d1, d2, acc[8];
};

// Term 0 of column m (W_m = sect; its K, L, F, G and D terms are zero).
template <class V>
MERIDIAN_INLINE void column_begin(double c0, double s0, double sect, ColumnState<V>& st) {
  st.w1 = sect + V{};
  st.w2 = st.d1 = st.d2 = V{};
  st.acc[0] = c0 * st.w1;
  st.acc[1] = s0 * st.w1;
  for (int j = 2; j < 8; ++j) st.acc[j] = V{};
}

// The per-term values of one column segment that every group of a pass shares: α, β and, for
// the derivatives, f C̄, f S̄ (the identity's sums) and (n − m) C̄, (n − m) S̄ (one multiply-add
// per term and group instead of a running n − m, which is a multiply and a scalar add chain).
struct Segment {
  alignas(64) double alpha[256], beta[256], fc[256], fs[256], kc[256], ks[256];
};

// The running values of one group in a column loop, as local variables (kept in registers).
template <class V>
struct Registers {
  V w1, w2, d1, d2, a0, b0, a1, b1, f0, f1, a2, b2;
  explicit MERIDIAN_INLINE Registers(const ColumnState<V>& st)
      : w1(st.w1), w2(st.w2), d1(st.d1), d2(st.d2), a0(st.acc[0]), b0(st.acc[1]), a1(st.acc[2]), b1(st.acc[3]),
        f0(st.acc[4]), f1(st.acc[5]), a2(st.acc[6]), b2(st.acc[7]) {}
  MERIDIAN_INLINE void store(ColumnState<V>& st) const {
    st.w1 = w1;
    st.w2 = w2;
    st.d1 = d1;
    st.d2 = d2;
    st.acc[0] = a0;
    st.acc[1] = b0;
    st.acc[2] = a1;
    st.acc[3] = b1;
    st.acc[4] = f0;
    st.acc[5] = f1;
    st.acc[6] = a2;
    st.acc[7] = b2;
  }
};

// Term i of a segment for one group (column_run). column_run_pair repeats its statements in the
// same form for two groups, so that a lane's sums are the same bits whichever loop ran them
// (the compiler contracts multiply-adds the same way in both; tested bit for bit).
template <Deriv Mode, class V>
MERIDIAN_INLINE void column_term(const double* c, const double* s, const Segment& seg, int i, const V& tq,
                                 const V& q, const V& q2, Registers<V>& r) {
  constexpr bool kIdentity = Mode == Deriv::Identity || Mode == Deriv::Both;
  constexpr bool kRecursion = Mode == Deriv::Recursion || Mode == Deriv::Both;
  const double ci = c[i], si = s[i], al = seg.alpha[i];
  const V bq2 = seg.beta[i] * q2, atq = al * tq;
  if constexpr (kIdentity) {
    r.f0 += seg.fc[i] * r.w1;  // F: f_nm C̄_nm W_{n−1}
    r.f1 += seg.fs[i] * r.w1;
  }
  const V w = atq * r.w1 - bq2 * r.w2;
  r.a0 += ci * w;
  r.b0 += si * w;
  if constexpr (Mode != Deriv::None) {
    r.a1 += seg.kc[i] * w;  // K: (n − m) C̄_nm W_n
    r.b1 += seg.ks[i] * w;
  }
  if constexpr (kRecursion) {
    // Written so that only one multiply-add depends on d1 (short chain).
    const V d = atq * r.d1 + ((al * q) * r.w1 - bq2 * r.d2);
    r.a2 += ci * d;
    r.b2 += si * d;
    r.d2 = r.d1;
    r.d1 = d;
  }
  r.w2 = r.w1;
  r.w1 = w;
}

// Terms k0 … k0 + len − 1 (k0 ≥ 1) of column m for one group: c, s point at term k0's C̄, S̄,
// seg holds the segment's shared values.
template <Deriv Mode, class V>
MERIDIAN_INLINE void column_run(const double* c, const double* s, const Segment& seg, int len, const V& tq,
                                const V& q, const V& q2, ColumnState<V>& st) {
  Registers<V> r(st);
  for (int i = 0; i < len; ++i) column_term<Mode, V>(c, s, seg, i, tq, q, q2, r);
  r.store(st);
}

// Two groups in one loop (Mode None or Identity), sharing the loads: one group alone waits on
// W_{n−1}, a multiply-add latency, every term; two independent recursions fill that wait.
// 256 points at degree 360, against the same identity one group at a time: −21 % (SSE2), −8 %
// (AVX-512), −5 % (AVX2, whose 16 registers cannot hold both groups' sums: three of them live
// on the stack). Each group's statements are
// column_term's, in the same form (so the same multiply-adds and the same bits); the two groups'
// statements are interleaved by hand, which the register allocator needs on AVX2 (column_term
// called twice spilled twice as much).
template <Deriv Mode, class V>
MERIDIAN_INLINE void column_run_pair(const double* c, const double* s, const Segment& seg, int len, const V& tq0,
                                     const V& q20, const V& tq1, const V& q21, ColumnState<V>* st) {
  static_assert(Mode == Deriv::None || Mode == Deriv::Identity);
  constexpr bool kIdentity = Mode == Deriv::Identity;
  Registers<V> g(st[0]), h(st[1]);
  for (int i = 0; i < len; ++i) {
    const double ci = c[i], si = s[i], al = seg.alpha[i], be = seg.beta[i];
    if constexpr (kIdentity) {
      const double fc = seg.fc[i], fs = seg.fs[i];
      g.f0 += fc * g.w1;
      g.f1 += fs * g.w1;
      h.f0 += fc * h.w1;
      h.f1 += fs * h.w1;
    }
    const V w = (al * tq0) * g.w1 - (be * q20) * g.w2;
    const V x = (al * tq1) * h.w1 - (be * q21) * h.w2;
    g.a0 += ci * w;
    g.b0 += si * w;
    h.a0 += ci * x;
    h.b0 += si * x;
    if constexpr (kIdentity) {
      const double kc = seg.kc[i], ks = seg.ks[i];
      g.a1 += kc * w;
      g.b1 += ks * w;
      h.a1 += kc * x;
      h.b1 += ks * x;
    }
    g.w2 = g.w1;
    g.w1 = w;
    h.w2 = h.w1;
    h.w1 = x;
  }
  g.store(st[0]);
  h.store(st[1]);
}

// Terms per segment: the segment's shared values (12 KB) and C̄, S̄ (4 KB) stay in the L1 cache
// while every group of the pass runs its recursion over them (a whole column at degree 2190
// is 35 KB of C̄, S̄).
inline constexpr int kSegmentTerms = 256;
static_assert(sizeof(Segment::alpha) == kSegmentTerms * sizeof(double));

// The shared values of n = m + k, k = k0 … k0 + len − 1 (k0 ≥ 1): α_nm, β_nm as the products
// the table-building code formed before (bit for bit), from contiguous tables so that the loop
// vectorises, β_{m+1,m} = 0; and when `grad`, f_nm C̄_nm, f_nm S̄_nm, k C̄_nm, k S̄_nm.
MERIDIAN_INLINE void segment_values(const RootTables& r, int m, int k0, int len, const double* c, const double* s,
                                    bool grad, Segment& seg) {
  const double* inv = r.inv_root.data();
  const double* root = r.root.data();
  const double* p1 = r.r2p1.data();
  const double* m1 = r.r2m1.data();
  const double* m3 = r.inv_r2m3.data();
  const double* im1 = r.inv_r2m1.data();
  const int n0 = m + k0;
  for (int i = 0; i < len; ++i) {
    const int n = n0 + i;
    const double common = inv[n - m] * inv[n + m] * p1[n];
    seg.alpha[i] = common * m1[n];
    seg.beta[i] = common * root[n + m - 1] * root[n - m - 1] * m3[n];
  }
  if (k0 == 1) seg.beta[0] = 0.0;  // n = m + 1 (for m = 0, n = 1 the tables hold 1/√(−1) as 0 anyway)
  if (!grad) return;
  for (int i = 0; i < len; ++i) {
    const int n = n0 + i;
    const double f = p1[n] * root[n - m] * root[n + m] * im1[n];  // f_nm, n ≥ 1
    const double k = k0 + i;
    seg.fc[i] = f * c[i];
    seg.fs[i] = f * s[i];
    seg.kc[i] = k * c[i];
    seg.ks[i] = k * s[i];
  }
}

// A group's lanes in the kernel's variables, which of them are near a pole, and the form of
// the t-derivative the group computes.
template <class V, int W>
struct GroupGeometry {
  V t, q, tq, q2, inv_u2;
  bool near_pole[W];
  Deriv mode;
};

// For lanes (t_i, q_i), with u² = (1 − t)(1 + t) (accurate near the poles).
template <class V, int W>
MERIDIAN_INLINE GroupGeometry<V, W> group_geometry(const V& t, const V& q, bool grad) {
  GroupGeometry<V, W> g;
  g.t = t;
  g.q = q;
  g.tq = t * q;
  g.q2 = q * q;
  const V u2 = (1.0 - t) * (1.0 + t);
  int near = 0;
  for (int i = 0; i < W; ++i) {
    g.near_pole[i] = !(u2[i] >= kIdentityMinCos * kIdentityMinCos);
    near += g.near_pole[i];
    g.inv_u2[i] = g.near_pole[i] ? 0.0 : 1.0 / u2[i];  // unused near the poles (no division by zero)
  }
  g.mode = !grad ? Deriv::None : near == 0 ? Deriv::Identity : near == W ? Deriv::Recursion : Deriv::Both;
  return g;
}

// One column m for `groups` groups of lanes: st[g] receives the sums of group g, in the form
// geo[g].mode. Neighbouring groups by the identity (or values only) run in pairs.
template <class V, int W>
MERIDIAN_INLINE void columns(const KernelData& d, int m, int next_m, const GroupGeometry<V, W>* geo, int groups,
                             ColumnState<V>* st) {
  const std::size_t k = d.start[m];
  const double* c = d.c + k;
  const double* s = d.s + k;
  const int count = d.nmax - m + 1;
  const bool grad = geo[0].mode != Deriv::None;
  for (int g = 0; g < groups; ++g) column_begin(c[0], s[0], d.sect[m], st[g]);
  Segment seg;
  for (int k0 = 1; k0 < count; k0 += kSegmentTerms) {
    const int len = std::min(count - k0, kSegmentTerms);
    segment_values(*d.roots, m, k0, len, c + k0, s + k0, grad, seg);
    // The next segment's C̄, S̄ (or the first of column next_m; −1: none) into the cache while
    // the groups run on this one, so that the next segment_values does not wait on memory
    // (degree 2190, 16 points, AVX2: −3 %; the hardware prefetcher alone fell behind).
    {
      const double *nc = nullptr, *ns = nullptr;
      int nlen = 0;
      if (k0 + len < count) {
        nc = c + k0 + len;
        ns = s + k0 + len;
        nlen = std::min(count - k0 - len, kSegmentTerms);
      } else if (next_m >= 0) {
        nc = d.c + d.start[next_m];
        ns = d.s + d.start[next_m];
        nlen = std::min(d.nmax - next_m + 1, kSegmentTerms + 1);
      }
      for (int b = 0; b < nlen; b += 8) {
        __builtin_prefetch(nc + b, 0, 3);
        __builtin_prefetch(ns + b, 0, 3);
      }
    }
    const double *cs = c + k0, *ss = s + k0;
    for (int g = 0; g < groups; ++g) {
      const GroupGeometry<V, W>& a = geo[g];
      const bool pairable = a.mode == Deriv::None || a.mode == Deriv::Identity;
      if (pairable && g + 1 < groups && geo[g + 1].mode == a.mode) {
        const GroupGeometry<V, W>& b = geo[g + 1];
        if (a.mode == Deriv::None)
          column_run_pair<Deriv::None, V>(cs, ss, seg, len, a.tq, a.q2, b.tq, b.q2, st + g);
        else
          column_run_pair<Deriv::Identity, V>(cs, ss, seg, len, a.tq, a.q2, b.tq, b.q2, st + g);
        ++g;
        continue;
      }
      switch (a.mode) {
        case Deriv::None: column_run<Deriv::None, V>(cs, ss, seg, len, a.tq, a.q, a.q2, st[g]); break;
        case Deriv::Identity: column_run<Deriv::Identity, V>(cs, ss, seg, len, a.tq, a.q, a.q2, st[g]); break;
        case Deriv::Recursion: column_run<Deriv::Recursion, V>(cs, ss, seg, len, a.tq, a.q, a.q2, st[g]); break;
        case Deriv::Both: column_run<Deriv::Both, V>(cs, ss, seg, len, a.tq, a.q, a.q2, st[g]); break;
      }
    }
  }
}

// The sums of order m that the combination reads, from a group's column state: A0, B0,
// A1 = K + (m + 1) A0, B1 = L + (m + 1) B0, and A2, B2: by the identity, (q F − t K)/u², or
// near a pole from the recursion.
template <bool Grad, class V, int W>
MERIDIAN_INLINE void order_sums(const ColumnState<V>& st, int m, const GroupGeometry<V, W>& g, V out[6]) {
  const V* a = st.acc;
  out[0] = a[0];
  out[1] = a[1];
  if constexpr (Grad) {
    const double mp1 = m + 1;
    out[2] = a[2] + mp1 * a[0];
    out[3] = a[3] + mp1 * a[1];
    if (g.mode == Deriv::Recursion) {
      out[4] = a[6];
      out[5] = a[7];
      return;
    }
    out[4] = (g.q * a[4] - g.t * a[2]) * g.inv_u2;
    out[5] = (g.q * a[5] - g.t * a[3]) * g.inv_u2;
    if (g.mode == Deriv::Both)
      for (int i = 0; i < W; ++i)
        if (g.near_pole[i]) {
          out[4][i] = a[6][i];
          out[5][i] = a[7][i];
        }
  }
}

// h = h z + (a − i b)
template <class V>
MERIDIAN_INLINE void horner_step(V& hr, V& hi, const V& zr, const V& zi, const V& a, const V& b) {
  const V r = hr * zr - hi * zi + a;
  hi = hr * zi + hi * zr - b;
  hr = r;
}

// Up to P·W points as P groups of W lanes of type V (the kernel's native width). The groups
// share each column m segment by segment while it is in the L1 cache (columns): the coefficient
// table is streamed from memory once per pass, however narrow the vectors, and a loop keeps one
// group's recursion, or a pair's, in registers.
template <bool Grad, class V, int W, int P>
MERIDIAN_INLINE void evaluate_impl(const KernelData& d, const LanePoint* pts, int count, LaneSums* out) {
  struct Group {  // t and q are in the group's geometry
    V u, cl, sl, zr, zi;
    V h0r{}, h0i{}, h1r{}, h1i{}, h2r{}, h2i{}, gr{}, gi{};
  };
  Group g[P];
  GroupGeometry<V, W> geo[P]{};
  const int groups = (count + W - 1) / W;
  for (int k = 0; k < groups; ++k) {
    Group& G = g[k];
    V t{}, q{};
    for (int i = 0; i < W; ++i) {
      const LanePoint& p = pts[std::min(k * W + i, count - 1)];
      t[i] = p.t;
      G.u[i] = p.u;
      q[i] = p.q;
      G.cl[i] = p.cos_lon;
      G.sl[i] = p.sin_lon;
    }
    G.zr = G.u * q * G.cl;
    G.zi = G.u * q * G.sl;
    geo[k] = group_geometry<V, W>(t, q, Grad);
  }
  ColumnState<V> st[P]{};
  for (int m = d.mmax; m >= 0; --m) {
    columns<V, W>(d, m, m - 1, geo, groups, st);
    for (int k = 0; k < groups; ++k) {
      Group& G = g[k];
      V acc[6];
      order_sums<Grad, V, W>(st[k], m, geo[k], acc);
      horner_step(G.h0r, G.h0i, G.zr, G.zi, acc[0], acc[1]);
      if constexpr (Grad) {
        horner_step(G.h1r, G.h1i, G.zr, G.zi, acc[2], acc[3]);
        horner_step(G.h2r, G.h2i, G.zr, G.zi, acc[4], acc[5]);
        if (m >= 1)
          horner_step(G.gr, G.gi, G.zr, G.zi, static_cast<double>(m) * acc[0], static_cast<double>(m) * acc[1]);
      }
    }
  }
  for (int j = 0; j < count; ++j) {
    const Group& G = g[j / W];
    const GroupGeometry<V, W>& geo_j = geo[j / W];
    const int i = j % W;
    LaneSums& o = out[j];
    const double q = geo_j.q[i];
    o.v = q * G.h0r[i] * kInvScale;
    if constexpr (Grad) {
      // G e^{iλ}: real part Σ u^{m−1} m X_m, minus imaginary part the east sum.
      const double g0 = G.gr[i] * G.cl[i] - G.gi[i] * G.sl[i], g3 = -(G.gr[i] * G.sl[i] + G.gi[i] * G.cl[i]);
      o.dr = q * G.h1r[i] * kInvScale;
      o.dn = (q * G.u[i] * G.h2r[i] - q * q * geo_j.t[i] * g0) * kInvScale;
      o.de = q * q * g3 * kInvScale;
    } else {
      o.dr = o.dn = o.de = 0;
    }
  }
}


// Column sums of up to P·W parallels (the grid's FFT path): P groups of W lanes share each column
// while it is in cache, as in evaluate_impl; lane i of group k is parallel k·W + i.
template <bool Grad, class V, int W, int P>
MERIDIAN_INLINE void column_sums_impl(const KernelData& d, const double* t, const double* q, int count,
                                      std::vector<double>* out) {
  constexpr std::size_t width = Grad ? 6 : 2;
  GroupGeometry<V, W> geo[P]{};
  const int groups = (count + W - 1) / W;
  for (int k = 0; k < groups; ++k) {
    V tv{}, qk{};
    for (int i = 0; i < W; ++i) {
      const int j = std::min(k * W + i, count - 1);  // spare lanes repeat the last parallel
      tv[i] = t[j];
      qk[i] = q[j];
    }
    geo[k] = group_geometry<V, W>(tv, qk, Grad);
  }
  for (int j = 0; j < count; ++j) out[j].resize(width * (static_cast<std::size_t>(d.mmax) + 1));
  ColumnState<V> st[P]{};
  for (int m = 0; m <= d.mmax; ++m) {
    const std::size_t o = width * static_cast<std::size_t>(m);
    columns<V, W>(d, m, m < d.mmax ? m + 1 : -1, geo, groups, st);
    for (int k = 0; k < groups; ++k) {
      V acc[6];
      order_sums<Grad, V, W>(st[k], m, geo[k], acc);
      for (int i = 0; i < W && k * W + i < count; ++i) {
        double* s = out[k * W + i].data() + o;
        for (std::size_t c = 0; c < width; ++c) s[c] = acc[c][i];
      }
    }
  }
}

typedef double V2 __attribute__((vector_size(2 * sizeof(double))));

// One function per kernel (gravity/simd_kernel.hpp), each in its native vector width; chosen
// at run time by SynthesisTable::evaluate. Explicit target attributes rather than
// target_clones: a clone cannot know its own width, and the 8-lane vectors that suit
// AVX-512 spill on AVX2 (issue 14).
#if defined(__x86_64__) && !defined(MERIDIAN_NO_TARGET_CLONES)
#define MERIDIAN_HAVE_X86_KERNELS 1
template <bool Grad>
__attribute__((target("arch=x86-64-v4"))) void evaluate_v4(const KernelData& d,
                                                           const LanePoint* pts, int count, LaneSums* out) {
  // 8 lanes whatever the count: a 256-bit pass for up to 4 points (half the work on AMD Zen 4,
  // which splits 512-bit operations) gave other last bits than the 8-lane loop under this
  // target, so a point's values depended on the size of its batch.
  evaluate_impl<Grad, V8, kLanes, kPointsPerPass / kLanes>(d, pts, count, out);
}

template <bool Grad>
__attribute__((target("arch=x86-64-v3"))) void evaluate_v3(const KernelData& d,
                                                           const LanePoint* pts, int count, LaneSums* out) {
  evaluate_impl<Grad, V4, 4, kPointsPerPass / 4>(d, pts, count, out);
}

template <bool Grad>
__attribute__((target("arch=x86-64-v4"))) void column_sums_v4(const KernelData& d, const double* t, const double* q, int count,
                                                              std::vector<double>* out) {
  column_sums_impl<Grad, V8, kLanes, kBlockParallels / kLanes>(d, t, q, count, out);
}

template <bool Grad>
__attribute__((target("arch=x86-64-v3"))) void column_sums_v3(const KernelData& d, const double* t, const double* q, int count,
                                                              std::vector<double>* out) {
  column_sums_impl<Grad, V4, 4, kBlockParallels / 4>(d, t, q, count, out);
}
#endif

template <bool Grad>
void evaluate_baseline(const KernelData& d, const LanePoint* pts, int count, LaneSums* out) {
  evaluate_impl<Grad, V2, 2, kPointsPerPass / 2>(d, pts, count, out);
}

template <bool Grad>
void evaluate_with(SimdKernel kernel, const KernelData& d, const LanePoint* pts, int count, LaneSums* out) {
#ifdef MERIDIAN_HAVE_X86_KERNELS
  if (kernel == SimdKernel::X86_64_V4) return evaluate_v4<Grad>(d, pts, count, out);
  if (kernel == SimdKernel::X86_64_V3) return evaluate_v3<Grad>(d, pts, count, out);
#else
  (void)kernel;
#endif
  evaluate_baseline<Grad>(d, pts, count, out);
}

template <bool Grad>
void column_sums_with(SimdKernel kernel, const KernelData& d, const double* t, const double* q, int count,
                      std::vector<double>* out) {
#ifdef MERIDIAN_HAVE_X86_KERNELS
  if (kernel == SimdKernel::X86_64_V4) return column_sums_v4<Grad>(d, t, q, count, out);
  if (kernel == SimdKernel::X86_64_V3) return column_sums_v3<Grad>(d, t, q, count, out);
#else
  (void)kernel;
#endif
  column_sums_impl<Grad, V2, 2, kBlockParallels / 2>(d, t, q, count, out);
}

}  // namespace

KernelData SynthesisTable::kernel_data() const noexcept {
  return {coefficients_.c_values().data(), coefficients_.s_values().data(), start_.data(), sectoral_.data(), &roots_,
          n_, m_};
}

void SynthesisTable::evaluate(const LanePoint* points, int count, bool gradient, LaneSums* out) const {
  if (count <= 0) return;
  const KernelData d = kernel_data();
  if (gradient)
    evaluate_with<true>(kernel_, d, points, count, out);
  else
    evaluate_with<false>(kernel_, d, points, count, out);
}

std::vector<double> SynthesisTable::column_sums(double t, double q, bool gradient) const {
  std::vector<double> sums;
  column_sums(&t, &q, 1, gradient, &sums);
  return sums;
}

void SynthesisTable::column_sums(const double* t, const double* q, int count, bool gradient,
                                 std::vector<double>* out) const {
  const KernelData d = kernel_data();
  for (int first = 0; first < count; first += kBlockParallels) {
    const int n = std::min(kBlockParallels, count - first);
    if (gradient)
      column_sums_with<true>(kernel_, d, t + first, q + first, n, out + first);
    else
      column_sums_with<false>(kernel_, d, t + first, q + first, n, out + first);
  }
}

LaneSums SynthesisTable::horner(const std::vector<double>& sums, bool gradient, const LanePoint& p) const {
  const std::size_t width = gradient ? 6 : 2;
  const double zr = p.u * p.q * p.cos_lon, zi = p.u * p.q * p.sin_lon;
  double h0r = 0, h0i = 0, h1r = 0, h1i = 0, h2r = 0, h2i = 0, gr = 0, gi = 0;
  auto step = [&](double& hr, double& hi, double a, double b) {
    const double r = hr * zr - hi * zi + a;
    hi = hr * zi + hi * zr - b;
    hr = r;
  };
  for (int m = m_; m >= 0; --m) {
    const double* s = sums.data() + width * static_cast<std::size_t>(m);
    step(h0r, h0i, s[0], s[1]);
    if (gradient) {
      step(h1r, h1i, s[2], s[3]);
      step(h2r, h2i, s[4], s[5]);
      if (m >= 1) step(gr, gi, m * s[0], m * s[1]);
    }
  }
  LaneSums o{p.q * h0r * kInvScale, 0, 0, 0};
  if (gradient) {
    const double g0 = gr * p.cos_lon - gi * p.sin_lon, g3 = -(gr * p.sin_lon + gi * p.cos_lon);
    o.dr = p.q * h1r * kInvScale;
    o.dn = (p.q * p.u * h2r - p.q * p.q * p.t * g0) * kInvScale;
    o.de = p.q * p.q * g3 * kInvScale;
  }
  return o;
}

}  // namespace meridian::gravity::detail
