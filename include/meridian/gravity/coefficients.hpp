#pragma once
/// \file coefficients.hpp
/// Fully normalised spherical-harmonic coefficients C̄_nm, S̄_nm of a
/// potential, stored by order (column-major, as GeographicLib stores them):
/// m = 0: n = 0..N, then m = 1: n = 1..N, …, m = M: n = M..N. Memory is
/// proportional to the coefficients kept after truncation.

#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

#include "meridian/core/scratch_array.hpp"

namespace meridian::gravity {

/// An allocator that leaves doubles uninitialised where std::allocator would zero them
/// (construction without arguments is default-initialisation), for coefficient arrays that a
/// reader fills entirely: a 38 MB zero fill before the file's bytes overwrite it costs a
/// loaded model about 1.5 ms on the 2-core guest of docs/benchmarks.md.
template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  using std::allocator<T>::allocator;
  /// Large arrays are faulted in at once (meridian::populate_pages): 38 MB at degree 2190 are
  /// 9 400 page faults otherwise.
  T* allocate(std::size_t n) {
    T* p = std::allocator<T>::allocate(n);
    populate_pages(p, n * sizeof(T));
    return p;
  }
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// Coefficients of Σ_n Σ_m P̄_nm(sin ψ) (C̄_nm cos mλ + S̄_nm sin mλ) with the
/// geodesy normalisation (4π-normalised, no Condon–Shortley phase):
/// ∫ P̄_nm² cos² mλ dσ / 4π = 1. Dimensionless.
class SphericalHarmonicCoefficients {
 public:
  /// An all-zero set complete to degree `max_degree` (N ≥ 0) and order
  /// `max_order` (0 ≤ M ≤ N). Throws InputError otherwise.
  SphericalHarmonicCoefficients(int max_degree, int max_order);
  SphericalHarmonicCoefficients() : SphericalHarmonicCoefficients(0, 0) {}
  /// Marks the constructor below.
  struct Unfilled {};
  /// A set whose C̄ and S̄ (except S̄_n0, zero) are left for the caller to fill, every one of
  /// them, through c_data() and s_data() (file readers). Throws as the one above.
  SphericalHarmonicCoefficients(int max_degree, int max_order, Unfilled);

  /// Storage of C̄ or S̄ (a std::vector that is not zero-filled on resize).
  using Values = std::vector<double, DefaultInitAllocator<double>>;

  int max_degree() const noexcept { return n_; }
  int max_order() const noexcept { return m_; }
  /// Number of (n, m) pairs held (C̄ values; S̄_n0 are stored as zeros).
  std::size_t size() const noexcept { return c_.size(); }

  /// Position of (n, m) in the column-major arrays; requires 0 ≤ m ≤ M, m ≤ n ≤ N.
  std::size_t index(int n, int m) const noexcept {
    const std::size_t mm = static_cast<std::size_t>(m);
    return mm * static_cast<std::size_t>(2 * n_ + 3 - m) / 2 + static_cast<std::size_t>(n - m);
  }
  /// True when (n, m) lies inside the stored triangle/trapezium.
  bool contains(int n, int m) const noexcept { return m >= 0 && m <= m_ && n >= m && n <= n_; }

  double c(int n, int m) const noexcept { return c_[index(n, m)]; }
  double s(int n, int m) const noexcept { return s_[index(n, m)]; }
  void set(int n, int m, double c_nm, double s_nm) noexcept {
    c_[index(n, m)] = c_nm;
    s_[index(n, m)] = m == 0 ? 0.0 : s_nm;
  }

  /// Column-major raw arrays (see the file comment), size() each.
  const Values& c_values() const noexcept { return c_; }
  const Values& s_values() const noexcept { return s_; }
  /// Mutable raw arrays for readers filling whole columns (same layout).
  double* c_data() noexcept { return c_.data(); }
  double* s_data() noexcept { return s_.data(); }

  /// A copy keeping degrees ≤ max_degree and orders ≤ max_order (clamped to
  /// what is held; negative means "all").
  SphericalHarmonicCoefficients truncated(int max_degree, int max_order) const;

 private:
  int n_ = 0, m_ = 0;
  Values c_, s_;
};

}  // namespace meridian::gravity
