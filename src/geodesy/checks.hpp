#pragma once
// Private to the geodesy module (not installed): the input checks its functions share.

#include <cmath>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::geodesy::detail {

/// Throw InputError "<what> is not finite (v)" unless v is finite.
inline void require_finite(double v, const char* what) {
  if (!std::isfinite(v)) throw InputError(fmt::format("{} is not finite ({})", what, v));
}

}  // namespace meridian::geodesy::detail
