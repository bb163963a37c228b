#include "meridian/filter/innovation.hpp"

#include <limits>

#include "meridian/adjust/statistics.hpp"
#include "meridian/core/error.hpp"
#include "meridian/filter/detail/checks.hpp"

namespace meridian::filter {

InnovationGate::InnovationGate() { limits_.fill(std::numeric_limits<double>::infinity()); }

InnovationGate::InnovationGate(double alpha) : alpha_(alpha) {
  if (!(alpha > 0.0 && alpha < 1.0))
    throw InputError("significance level α of the innovation gate must be in (0, 1)");
  limits_[0] = 0.0;  // unused
  for (int m = 1; m <= kCached; ++m) limits_[m] = adjust::chi_squared_upper_quantile(alpha, m);
}

double InnovationGate::limit(Eigen::Index dof) const {
  if (dof < 1) throw InputError("the innovation gate needs at least one degree of freedom");
  if (!enabled()) return std::numeric_limits<double>::infinity();
  if (dof <= kCached) return limits_[static_cast<std::size_t>(dof)];
  return adjust::chi_squared_upper_quantile(alpha_, static_cast<double>(dof));
}

}  // namespace meridian::filter
