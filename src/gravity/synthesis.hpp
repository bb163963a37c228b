#pragma once
// Private: the spherical-harmonic summation kernel shared by GravityField
// and GravityCircle. See docs/gravity-field.md §3 for the formulas.

#include <cstddef>
#include <limits>
#include <memory>
#include <vector>

#include "meridian/gravity/coefficients.hpp"
#include "meridian/gravity/simd_kernel.hpp"

namespace meridian::gravity::detail {

/// The "not requested" value of FieldValues.
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Points in the widest vector (one AVX-512 register of doubles).
inline constexpr int kLanes = 8;
/// Scattered points evaluated in one pass over the coefficient table (evaluate): groups of
/// 8 (AVX-512), 4 (AVX2) or 2 (SSE2) lanes that share each column while it is in cache, so
/// the coefficients (C̄, S̄: 38 MB at degree 2190) are streamed from memory once per this many points.
inline constexpr int kPointsPerPass = 16;
/// Parallels whose column sums one pass over the coefficient table computes (the grid's FFT
/// path): two AVX-512 vectors, four AVX2, eight SSE2 — each column (≤ 70 KB at degree 2190)
/// is read from memory once and from cache for the other vectors.
inline constexpr int kBlockParallels = 16;
/// Scale applied to P̄_nm / cos^m ψ so that neither overflow nor underflow
/// occurs to degree ~2700 (Holmes & Featherstone 2002).
inline constexpr double kScale = 1e-280;
inline constexpr double kInvScale = 1e280;

/// A point in the kernel's variables: t = sin ψ, u = cos ψ (geocentric
/// latitude ψ), q = a/r, and the longitude's cosine and sine.
struct LanePoint {
  double t, u, q, cos_lon, sin_lon;
};

/// Σ_n Σ_m q^{n+1} P̄_nm(t)(C cos mλ + S sin mλ) and derivatives, so that
/// with K = GM/a: value = K·v, ∂/∂r = −(K/r)·dr, (1/r)∂/∂ψ = (K/r)·dn,
/// (1/(r cos ψ))∂/∂λ = (K/r)·de.
struct LaneSums {
  double v, dr, dn, de;
};

/// The recursion coefficients α_nm, β_nm of one degree n are products of entries of these
/// tables (√k and 1/√k, and per degree √(2n+1), √(2n−1), 1/√(2n−3)), formed for one segment of
/// a column at a time inside the kernel: no table of 2.4 million α, β (77 MB with C̄, S̄ at
/// degree 2190) to build when a model is loaded.
struct RootTables {
  std::vector<double> root, inv_root;         // √k, 1/√k (1/√0 = 0), k = 0 … 2N + 1
  std::vector<double> r2p1, r2m1, inv_r2m1, inv_r2m3;  // √(2n+1), √(2n−1), 1/√(2n−1), 1/√(2n−3), n = 0 … N (0 where undefined)
};

/// What the kernel reads: C̄, S̄ column-major, the index of (m, m) per column, the sectoral
/// seeds, the root tables for α, β. Borrowed from a SynthesisTable.
struct KernelData {
  const double* c;
  const double* s;
  const std::size_t* start;
  const double* sect;
  const RootTables* roots;
  int nmax, mmax;
};

class SynthesisTable {
 public:
  /// Takes the coefficients (move them in to avoid a copy). `kernel`: the instruction set of
  /// evaluate() (resolve_simd_kernel; InputError when this CPU cannot run it).
  explicit SynthesisTable(SphericalHarmonicCoefficients c, SimdKernel kernel = SimdKernel::Auto);

  int max_degree() const noexcept { return n_; }
  int max_order() const noexcept { return m_; }
  SimdKernel kernel() const noexcept { return kernel_; }  ///< concrete, never Auto
  /// Replace C̄_n0 (0 ≤ n ≤ N): for the owner's adjustments while it builds its tables.
  void set_zonal_c(int n, double c) noexcept { coefficients_.c_data()[coefficients_.index(n, 0)] = c; }
  double zonal_c(int n) const noexcept { return coefficients_.c(n, 0); }

  /// Evaluate 1..kPointsPerPass points (count) in one pass; dr/dn/de only when `gradient`.
  void evaluate(const LanePoint* points, int count, bool gradient, LaneSums* out) const;

  /// Per-order column sums for one (t, q) — 6 values per m when
  /// `gradient` (A0, B0, A1, B1, A2, B2), else 2 (A0, B0) — for circles.
  std::vector<double> column_sums(double t, double q, bool gradient) const;
  /// The column sums of `count` parallels, kBlockParallels at a time: `out[i]` (resized)
  /// receives what column_sums(t[i], q[i], gradient) returns, in the table's SIMD kernel. One
  /// pass over the coefficients for the whole block instead of one per parallel: the grid's
  /// FFT path, where the sums are the O(N²) part per parallel (issue 14).
  void column_sums(const double* t, const double* q, int count, bool gradient, std::vector<double>* out) const;
  /// Combine column sums at one longitude (the O(M) part).
  LaneSums horner(const std::vector<double>& sums, bool gradient, const LanePoint& p) const;

 private:
  KernelData kernel_data() const noexcept;

  int n_ = 0, m_ = 0;
  SimdKernel kernel_ = SimdKernel::Baseline;
  SphericalHarmonicCoefficients coefficients_;  // C̄, S̄ column-major (m = 0..M, n = m..N)
  RootTables roots_;
  std::vector<std::size_t> start_;  // index of (m, m) in the coefficient arrays
  std::vector<double> sectoral_;    // kScale · P̄_mm / cos^m ψ
};

}  // namespace meridian::gravity::detail
