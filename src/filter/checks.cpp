#include "meridian/filter/detail/checks.hpp"

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::filter::detail {

std::string epoch_field(Eigen::Index epoch) { return fmt::format("epoch {}", epoch); }

void throw_non_finite(const char* name, Eigen::Index epoch, Eigen::Index row, Eigen::Index col,
                      double value) {
  throw InputError(fmt::format("{} has a non-finite value ({}) at ({}, {})", name, value, row, col),
                   ErrorContext{{}, {}, epoch_field(epoch)});
}

void throw_input(Eigen::Index epoch, const std::string& message) {
  throw InputError(message, ErrorContext{{}, {}, epoch_field(epoch)});
}

void throw_numerical(Eigen::Index epoch, const std::string& message) {
  throw NumericalError(message, ErrorContext{{}, {}, epoch_field(epoch)});
}

void throw_not_positive_definite(const char* name, Eigen::Index epoch,
                                 const Eigen::Ref<const Eigen::MatrixXd>& m) {
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    if (!(std::isfinite(m(i, i)) && m(i, i) > 0.0))
      throw_numerical(epoch, fmt::format("{} is not positive definite: diagonal element {} is {}",
                                         name, i, m(i, i)));
  if (!m.allFinite()) throw_numerical(epoch, fmt::format("{} has a non-finite entry", name));
  throw_numerical(epoch, fmt::format("{} is not positive definite", name));
}

void throw_shape(Eigen::Index rows, Eigen::Index cols, Eigen::Index expected_rows,
                 Eigen::Index expected_cols, const char* name, Eigen::Index epoch) {
  throw_input(epoch, fmt::format("{} is {}×{}, expected {}×{}", name, rows, cols, expected_rows,
                                 expected_cols));
}

}  // namespace meridian::filter::detail
