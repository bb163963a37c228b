#include "meridian/maglev/series.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "context.hpp"
#include "meridian/core/error.hpp"

namespace meridian::maglev {
using detail::at;

void validate_series(const PositionSeries& s, const std::string& field) {
  if (s.current_A.empty()) throw InputError("the series is empty", at(field + ".current_A"));
  if (s.time_s.size() != s.current_A.size())
    throw InputError(fmt::format("{} times for {} currents", s.time_s.size(), s.current_A.size()),
                     at(field + ".time_s"));
  for (std::size_t i = 0; i < s.current_A.size(); ++i) {
    if (!std::isfinite(s.current_A[i]))
      throw InputError(fmt::format("sample {} is not a finite number", i),
                       at(fmt::format("{}.current_A[{}]", field, i)));
    if (!std::isfinite(s.time_s[i]))
      throw InputError(fmt::format("time {} is not a finite number", i),
                       at(fmt::format("{}.time_s[{}]", field, i)));
    if (i > 0 && !(s.time_s[i] > s.time_s[i - 1]))
      throw InputError(
          fmt::format("time does not increase ({} s after {} s)", s.time_s[i], s.time_s[i - 1]),
          at(fmt::format("{}.time_s[{}]", field, i)));
  }
  const auto [lo, hi] = std::minmax_element(s.current_A.begin(), s.current_A.end());
  if (*lo == *hi)
    throw InputError(
        fmt::format("no variation in the series (every sample is {} A): a mean with a σ needs "
                    "noise (a noise-free simulation cannot be reduced)",
                    *lo),
        at(field + ".current_A"));
}

}  // namespace meridian::maglev
