#pragma once
/// \file checks.hpp
/// Internal: input checks of the filter templates and the throwing of errors that name the
/// epoch. The throwing functions live in src/filter/checks.cpp, so the hot templates carry only
/// a branch and a call on their failure path.

#include <cmath>
#include <string>

#include <Eigen/Core>

namespace meridian::filter::detail {

/// ErrorContext::field of an epoch: "epoch 1234".
std::string epoch_field(Eigen::Index epoch);

/// Throw InputError "<name> has a non-finite value (<value>) at (<row>, <col>)" naming the epoch.
[[noreturn]] void throw_non_finite(const char* name, Eigen::Index epoch, Eigen::Index row,
                                   Eigen::Index col, double value);
/// Throw InputError(message) naming the epoch.
[[noreturn]] void throw_input(Eigen::Index epoch, const std::string& message);
/// Throw NumericalError(message) naming the epoch.
[[noreturn]] void throw_numerical(Eigen::Index epoch, const std::string& message);
/// Throw NumericalError "<name> is not positive definite: …" naming the epoch, with the first
/// diagonal element that is not positive and finite when there is one.
[[noreturn]] void throw_not_positive_definite(const char* name, Eigen::Index epoch,
                                              const Eigen::Ref<const Eigen::MatrixXd>& m);

/// True when every entry of m is finite: Σ m_ij·0 is 0 exactly when no entry is ±∞ or NaN
/// (∞·0 and NaN·0 are NaN). One vectorised sum, where Eigen's allFinite() is a chain of scalar
/// compares and branches for fixed sizes.
template <typename Derived>
inline bool all_finite(const Eigen::MatrixBase<Derived>& m) {
  return (m.derived().array() * 0.0).sum() == 0.0;
}

/// InputError naming the epoch unless every entry of m is finite.
template <typename Derived>
inline void check_finite(const Eigen::MatrixBase<Derived>& m, const char* name,
                         Eigen::Index epoch) {
  if (all_finite(m)) [[likely]]
    return;
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      if (!std::isfinite(m(i, j))) throw_non_finite(name, epoch, i, j, m(i, j));
}

/// Throw InputError "<name> is <rows>×<cols>, expected …" naming the epoch.
[[noreturn]] void throw_shape(Eigen::Index rows, Eigen::Index cols, Eigen::Index expected_rows,
                              Eigen::Index expected_cols, const char* name, Eigen::Index epoch);

/// InputError naming the epoch unless m has `rows`×`cols` entries (dynamic sizes; inline, so
/// a no-op for fixed sizes that already match).
inline void check_shape(Eigen::Index rows, Eigen::Index cols, Eigen::Index expected_rows,
                        Eigen::Index expected_cols, const char* name, Eigen::Index epoch) {
  if (rows != expected_rows || cols != expected_cols) [[unlikely]]
    throw_shape(rows, cols, expected_rows, expected_cols, name, epoch);
}

/// NumericalError naming the epoch unless P has a positive, finite diagonal (a cheap test
/// of a covariance after each step; full positive definiteness is tested where P is
/// factored).
template <typename Derived>
inline void check_covariance_diagonal(const Eigen::MatrixBase<Derived>& P, const char* name,
                                      Eigen::Index epoch) {
  if (all_finite(P) && (P.diagonal().array() > 0.0).all()) [[likely]]
    return;
  throw_not_positive_definite(name, epoch, P);
}

}  // namespace meridian::filter::detail
