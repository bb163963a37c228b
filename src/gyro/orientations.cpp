#include "meridian/gyro/orientations.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"

namespace meridian::gyro {

bool OrientationsResult::all_checks_pass() const {
  return std::all_of(checks.begin(), checks.end(), [](const Check& c) { return c.pass; });
}

OrientationsResult combine_orientations(const std::vector<CampaignResult>& in) {
  if (in.size() < 2)
    throw InputError(fmt::format("two or more independent orientations are needed, got {}", in.size()),
                     {"", std::nullopt, "orientations"});
  OrientationsResult r;
  const RegulationLimits& limits = in.front().limits;
  r.limits = limits;
  r.station = in.front().station.name;
  r.target = in.front().target ? in.front().target->name : std::string();
  for (std::size_t i = 0; i < in.size(); ++i) {
    const CampaignResult& c = in[i];
    const std::string target = c.target ? c.target->name : std::string();
    if (c.station.name != r.station || target != r.target)
      throw InputError(fmt::format("orientation {} is of the line {}-{}, not {}-{}", i + 1, c.station.name, target,
                                   r.station, r.target),
                       {"", std::nullopt, fmt::format("orientations[{}]", i)});
    r.grid_azimuths_rad.push_back(c.chain.grid_azimuth_rad);
  }
  r.mean = mean_direction(r.grid_azimuths_rad);
  const std::string source = limits.source;
  r.checks.push_back({"independent orientations, largest difference of the grid azimuths",
                      r.mean.max_difference / units::kArcsecond, limits.orientation_difference_rad / units::kArcsecond,
                      CheckUnit::Arcsec, r.mean.max_difference <= limits.orientation_difference_rad, false, source});
  r.checks.push_back({"independent orientations, sigma of the mean", r.mean.mean.sigma / units::kArcsecond,
                      limits.orientation_mean_sigma_rad / units::kArcsecond, CheckUnit::Arcsec,
                      r.mean.mean.sigma <= limits.orientation_mean_sigma_rad, false, source});
  r.notes.push_back(fmt::format("sigma of the mean: the larger of propagated {:.1f}\" and empirical {:.1f}\"",
                                r.mean.sigma_propagated / units::kArcsecond,
                                r.mean.sigma_empirical / units::kArcsecond));
  return r;
}

}  // namespace meridian::gyro
