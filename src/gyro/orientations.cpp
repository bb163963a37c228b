#include "meridian/gyro/orientations.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "meridian/core/angle.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"

namespace meridian::gyro {

bool OrientationsResult::all_checks_pass() const {
  return std::all_of(checks.begin(), checks.end(), [](const Check& c) { return c.pass; });
}

double point_distance_m(const PointResult& a, const PointResult& b) {
  // Two points a few metres apart at most matter: a sphere of the mean radius is exact to 0.5 %.
  constexpr double kRadius_m = 6371000.0;
  const double dn = (b.lat_rad - a.lat_rad) * kRadius_m;
  const double de = wrap_signed_rad(b.lon_rad - a.lon_rad) * std::cos(0.5 * (a.lat_rad + b.lat_rad)) * kRadius_m;
  return std::hypot(dn, de);
}

OrientationsResult combine_orientations(const std::vector<CampaignResult>& in) {
  if (in.size() < 2)
    throw InputError(fmt::format("two or more independent orientations are needed, got {}", in.size()),
                     {"", std::nullopt, "orientations"});
  OrientationsResult r;
  // The tightest limits of the orientations (their classes or files may differ).
  RegulationLimits limits = in.front().limits;
  for (const CampaignResult& c : in) {
    if (c.limits.orientation_difference_rad < limits.orientation_difference_rad) {
      limits.orientation_difference_rad = c.limits.orientation_difference_rad;
      limits.source = c.limits.source;
    }
    limits.orientation_mean_sigma_rad = std::min(limits.orientation_mean_sigma_rad, c.limits.orientation_mean_sigma_rad);
  }
  r.limits = limits;
  for (const CampaignResult& c : in) r.files.push_back(c.input.file);
  r.station = in.front().station.name;
  r.target = in.front().target ? in.front().target->name : std::string();
  for (std::size_t i = 0; i < in.size(); ++i) {
    const CampaignResult& c = in[i];
    const std::string field = fmt::format("orientations[{}]", i);
    // The same line is the same points: by their coordinates (names may be written differently,
    // "Ⅱ3" and a full-width "Ⅱ３"; a point moved keeps its name), by name where one has none.
    const auto same_point = [&](const PointResult& p, const PointResult& q, const char* role) {
      const double d = point_distance_m(p, q);
      if (d > kSamePointTolerance_m)
        throw InputError(fmt::format("orientation {}: its {} {} is {:.3f} m from the {} {} of orientation 1 (limit "
                                     "{:.2f} m): not the same line",
                                     i + 1, role, p.name, d, role, q.name, kSamePointTolerance_m),
                         {"", std::nullopt, field});
      if (p.name != q.name && i > 0)
        r.notes.push_back(fmt::format("orientation {}: its {} is named {} and {} in orientation 1; the same point by its "
                                      "coordinates ({:.3f} m apart)",
                                      i + 1, role, p.name, q.name, d));
    };
    same_point(c.station, in.front().station, "station");
    if (c.target && in.front().target) {
      same_point(*c.target, *in.front().target, "target");
    } else {
      const std::string target = c.target ? c.target->name : std::string();
      if (target != r.target)
        throw InputError(fmt::format("orientation {} is of the line {}-{}, not {}-{}", i + 1, c.station.name, target,
                                     r.station, r.target),
                         {"", std::nullopt, field});
    }
    // The same runs twice are one orientation, not two independent ones.
    for (std::size_t j = 0; j < i; ++j) {
      const auto& a = in[j].gyro_azimuths;
      const auto& b = c.gyro_azimuths;
      const bool same = a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](const auto& x, const auto& y) {
                          return x.value == y.value && x.sigma == y.sigma;
                        });
      if (same)
        throw InputError(fmt::format("orientations {} and {} have the same runs on the line: they are not independent",
                                     j + 1, i + 1),
                         {"", std::nullopt, fmt::format("orientations[{}]", i)});
    }
    r.grid_azimuths_rad.push_back(c.chain.grid_azimuth_rad);
  }
  for (std::size_t i = 0; i < in.size(); ++i) {
    int failed = 0;
    for (const auto& k : in[i].checks) failed += k.pass ? 0 : 1;
    r.checks.push_back({fmt::format("orientation {}: failed checks of its own", i + 1), static_cast<double>(failed),
                        0.0, CheckUnit::Checks, failed == 0, false, false,
                        "every orientation must pass its own checks", fmt::format("orientations[{}]", i)});
  }
  r.mean = mean_direction(r.grid_azimuths_rad);
  r.checks.push_back({"independent orientations, largest difference of the grid azimuths",
                      r.mean.max_difference / units::kArcsecond, limits.orientation_difference_rad / units::kArcsecond,
                      CheckUnit::Arcsec, r.mean.max_difference <= limits.orientation_difference_rad, false, false,
                      limits.source, ""});
  r.checks.push_back({"independent orientations, sigma of the mean", r.mean.mean.sigma / units::kArcsecond,
                      limits.orientation_mean_sigma_rad / units::kArcsecond, CheckUnit::Arcsec,
                      r.mean.mean.sigma <= limits.orientation_mean_sigma_rad, false, false, limits.source, ""});
  r.notes.push_back(fmt::format("sigma of the mean: the larger of propagated {:.1f}\" and empirical {:.1f}\"",
                                r.mean.sigma_propagated / units::kArcsecond,
                                r.mean.sigma_empirical / units::kArcsecond));
  return r;
}

}  // namespace meridian::gyro
