#pragma once
// Private to the gravity module: the one error of a model value that is not finite (a model
// whose coefficients, GM or radius are out of range), thrown by GravityField::evaluate (field
// "points[i]") and evaluate_parallels (field "points[i, j]"), so the two read alike.

#include <optional>
#include <string>
#include <utility>

#include "meridian/core/error.hpp"

namespace meridian::gravity::detail {

inline NumericalError model_value_not_finite(std::string field) {
  return NumericalError("the model gives a value that is not finite here: its coefficients, GM or reference radius "
                        "are out of range",
                        {"", std::nullopt, std::move(field)});
}

}  // namespace meridian::gravity::detail
