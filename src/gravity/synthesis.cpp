// The summation kernel. Compiled with -ffp-contract=fast and once per instruction set
// (gravity/simd_kernel.hpp: baseline, AVX2 + FMA, AVX-512), chosen at run time, so one binary
// runs everywhere at full speed.
//
// For each order m (descending) and each of kLanes points at once, the
// forward column recursion over n of W_n = q^{n−m} P̄_nm(t)/u^m · kScale:
//   W_n = α_nm t q W_{n−1} − β_nm q² W_{n−2},   W_m = kScale · P̄_mm/u^m,
// and of its t-derivative D_n = α_nm q (W_{n−1} + t D_{n−1}) − β_nm q² D_{n−2},
// accumulates A0 = Σ C W, B0 = Σ S W, A1 = Σ (n+1) C W, B1, A2 = Σ C D, B2.
// The orders are then combined by Horner's rule in z = u q e^{iλ}, which
// restores the u^m q^m factors without ever forming them (no underflow).

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
  roots_.inv_r2m3.assign(degrees, 0.0);
  for (std::size_t n = 0; n < degrees; ++n) {
    roots_.r2p1[n] = roots_.root[2 * n + 1];
    if (n >= 1) roots_.r2m1[n] = roots_.root[2 * n - 1];
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

// The forward recursion of one column for one group of lanes, resumable: W_{k−1}, W_{k−2},
// D_{k−1}, D_{k−2} and the six sums (A0, B0, A1, B1, A2, B2) after term k − 1.
template <class V>
struct ColumnState {
  V w1, w2, d1, d2, acc[6];
};

// Term 0 of column m (W_m = sect).
template <class V>
MERIDIAN_INLINE void column_begin(double c0, double s0, double sect, double m, ColumnState<V>& st) {
  st.w1 = sect + V{};
  st.w2 = st.d1 = st.d2 = V{};
  st.acc[0] = c0 * st.w1;
  st.acc[1] = s0 * st.w1;
  st.acc[2] = (m + 1) * st.acc[0];
  st.acc[3] = (m + 1) * st.acc[1];
  st.acc[4] = st.acc[5] = V{};
}

// The per-term values of one column segment that every group of a pass shares: α, β and, for
// the radial derivative's sums, (n + 1) C̄ and (n + 1) S̄ (formed once per segment instead of
// a running n + 1 per group, whose scalar add was a loop-carried chain).
struct Segment {
  alignas(64) double alpha[256], beta[256], c1[256], s1[256];
};

// Whether the radial sums take (n + 1) C̄, (n + 1) S̄ from the segment or multiply by a running
// n + 1. AVX-512: 5.79 → 5.31 ms for 256 points at degree 360 with the segment's values; AVX2:
// 8.59 → 8.85 ms, within the run-to-run scatter (two more broadcast loads per term against the
// scalar chain), so AVX2 and SSE2 keep the running n + 1.
template <class V>
inline constexpr bool kSharedNp1 = sizeof(V) >= 64;

// Terms k0 … k0 + len − 1 (k0 ≥ 1) of column m: c, s point at term k0's C̄, S̄, seg holds the
// segment's shared values, np1 = n + 1 of term k0 − 1. The state is kept in registers over the
// loop.
template <bool Grad, class V>
MERIDIAN_INLINE void column_run(const double* c, const double* s, const Segment& seg, int len, double np1,
                                const V& tq, const V& q, const V& q2, ColumnState<V>& st) {
  V w1 = st.w1, w2 = st.w2, d1 = st.d1, d2 = st.d2;
  V a0 = st.acc[0], b0 = st.acc[1], a1 = st.acc[2], b1 = st.acc[3], a2 = st.acc[4], b2 = st.acc[5];
  for (int i = 0; i < len; ++i) {
    const double ci = c[i], si = s[i], al = seg.alpha[i];
    const V bq2 = seg.beta[i] * q2, atq = al * tq;
    const V w = atq * w1 - bq2 * w2;
    a0 += ci * w;
    b0 += si * w;
    if constexpr (Grad) {
      // Written so that only one multiply-add depends on d1 (short chain).
      const V d = atq * d1 + ((al * q) * w1 - bq2 * d2);
      if constexpr (kSharedNp1<V>) {
        a1 += seg.c1[i] * w;
        b1 += seg.s1[i] * w;
      } else {
        np1 += 1;
        const V wn = np1 * w;
        a1 += ci * wn;
        b1 += si * wn;
      }
      a2 += ci * d;
      b2 += si * d;
      d2 = d1;
      d1 = d;
    }
    w2 = w1;
    w1 = w;
  }
  st.w1 = w1;
  st.w2 = w2;
  st.d1 = d1;
  st.d2 = d2;
  st.acc[0] = a0;
  st.acc[1] = b0;
  st.acc[2] = a1;
  st.acc[3] = b1;
  st.acc[4] = a2;
  st.acc[5] = b2;
}

// Terms per segment: the segment's shared values (8 KB) and C̄, S̄ (4 KB) stay in the L1 cache
// while every group of the pass runs its recursion over them (a whole column at degree 2190
// is 35 KB of C̄, S̄).
inline constexpr int kSegmentTerms = 256;
static_assert(sizeof(Segment::alpha) == kSegmentTerms * sizeof(double));

// The shared values of n = m + k, k = k0 … k0 + len − 1 (k0 ≥ 1): α_nm, β_nm as the products
// the table-building code formed before (bit for bit), from contiguous tables so that the loop
// vectorises, β_{m+1,m} = 0; and (n + 1) C̄_nm, (n + 1) S̄_nm when `grad`.
MERIDIAN_INLINE void segment_values(const RootTables& r, int m, int k0, int len, const double* c, const double* s,
                                    bool grad, Segment& seg) {
  const double* inv = r.inv_root.data();
  const double* root = r.root.data();
  const double* p1 = r.r2p1.data();
  const double* m1 = r.r2m1.data();
  const double* m3 = r.inv_r2m3.data();
  const int n0 = m + k0;
  for (int i = 0; i < len; ++i) {
    const int n = n0 + i;
    const double common = inv[n - m] * inv[n + m] * p1[n];
    seg.alpha[i] = common * m1[n];
    seg.beta[i] = common * root[n + m - 1] * root[n - m - 1] * m3[n];
  }
  if (k0 == 1) seg.beta[0] = 0.0;  // n = m + 1 (for m = 0, n = 1 the tables hold 1/√(−1) as 0 anyway)
  if (grad)
    for (int i = 0; i < len; ++i) {
      const double np1 = n0 + i + 1;
      seg.c1[i] = np1 * c[i];
      seg.s1[i] = np1 * s[i];
    }
}

// One column m for `groups` groups of lanes: st[g] receives the sums of group g.
template <bool Grad, class V>
MERIDIAN_INLINE void columns(const KernelData& d, int m, const V* tq, const V* q, const V* q2, int groups,
                             ColumnState<V>* st) {
  const std::size_t k = d.start[m];
  const double* c = d.c + k;
  const double* s = d.s + k;
  const int count = d.nmax - m + 1;
  for (int g = 0; g < groups; ++g) column_begin(c[0], s[0], d.sect[m], m, st[g]);
  Segment seg;
  for (int k0 = 1; k0 < count; k0 += kSegmentTerms) {
    const int len = std::min(count - k0, kSegmentTerms);
    segment_values(*d.roots, m, k0, len, c + k0, s + k0, Grad && kSharedNp1<V>, seg);
    for (int g = 0; g < groups; ++g)
      column_run<Grad, V>(c + k0, s + k0, seg, len, m + k0, tq[g], q[g], q2[g], st[g]);
  }
}

// h = h z + (a − i b)
template <class V>
MERIDIAN_INLINE void horner_step(V& hr, V& hi, const V& zr, const V& zi, const V& a, const V& b) {
  const V r = hr * zr - hi * zi + a;
  hi = hr * zi + hi * zr - b;
  hr = r;
}

// Up to P·W points as P groups of W lanes of type V (V8: kLanes points; V4 for small blocks:
// half the work on AVX2 and on AMD Zen 4, which splits 512-bit operations in two). The groups
// share each column m segment by segment while it is in the L1 cache (columns): the coefficient
// table is streamed from memory once per pass, however narrow the vectors, and the loop keeps
// only one group's recursion in registers.
template <bool Grad, class V, int W, int P>
MERIDIAN_INLINE void evaluate_impl(const KernelData& d, const LanePoint* pts, int count, LaneSums* out) {
  struct Group {
    V t, u, q, cl, sl, tq, q2, zr, zi;
    V h0r{}, h0i{}, h1r{}, h1i{}, h2r{}, h2i{}, gr{}, gi{};
  };
  Group g[P];
  const int groups = (count + W - 1) / W;
  for (int k = 0; k < groups; ++k) {
    Group& G = g[k];
    for (int i = 0; i < W; ++i) {
      const LanePoint& p = pts[std::min(k * W + i, count - 1)];
      G.t[i] = p.t;
      G.u[i] = p.u;
      G.q[i] = p.q;
      G.cl[i] = p.cos_lon;
      G.sl[i] = p.sin_lon;
    }
    G.tq = G.t * G.q;
    G.q2 = G.q * G.q;
    G.zr = G.u * G.q * G.cl;
    G.zi = G.u * G.q * G.sl;
  }
  V tq[P]{}, qv[P]{}, q2[P]{};
  for (int k = 0; k < groups; ++k) {
    tq[k] = g[k].tq;
    qv[k] = g[k].q;
    q2[k] = g[k].q2;
  }
  ColumnState<V> st[P]{};
  for (int m = d.mmax; m >= 0; --m) {
    columns<Grad, V>(d, m, tq, qv, q2, groups, st);
    for (int k = 0; k < groups; ++k) {
      Group& G = g[k];
      const V* acc = st[k].acc;
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
    const int i = j % W;
    LaneSums& o = out[j];
    const double q = G.q[i];
    o.v = q * G.h0r[i] * kInvScale;
    if constexpr (Grad) {
      // G e^{iλ}: real part Σ u^{m−1} m X_m, minus imaginary part the east sum.
      const double g0 = G.gr[i] * G.cl[i] - G.gi[i] * G.sl[i], g3 = -(G.gr[i] * G.sl[i] + G.gi[i] * G.cl[i]);
      o.dr = q * G.h1r[i] * kInvScale;
      o.dn = (q * G.u[i] * G.h2r[i] - q * q * G.t[i] * g0) * kInvScale;
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
  V tq[P]{}, qv[P]{}, q2[P]{};
  const int groups = (count + W - 1) / W;
  for (int k = 0; k < groups; ++k)
    for (int i = 0; i < W; ++i) {
      const int j = std::min(k * W + i, count - 1);  // spare lanes repeat the last parallel
      qv[k][i] = q[j];
      tq[k][i] = t[j] * q[j];
      q2[k][i] = q[j] * q[j];
    }
  for (int j = 0; j < count; ++j) out[j].resize(width * (static_cast<std::size_t>(d.mmax) + 1));
  ColumnState<V> st[P]{};
  for (int m = 0; m <= d.mmax; ++m) {
    const std::size_t o = width * static_cast<std::size_t>(m);
    columns<Grad, V>(d, m, tq, qv, q2, groups, st);
    for (int k = 0; k < groups; ++k) {
      const V* acc = st[k].acc;
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
  // Up to 4 points: one 256-bit pass does half the work (AMD Zen 4 splits 512-bit operations).
  if (count <= 4)
    evaluate_impl<Grad, V4, 4, 1>(d, pts, count, out);
  else
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
