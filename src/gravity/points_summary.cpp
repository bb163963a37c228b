#include "meridian/gravity/points_summary.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::gravity {

void RunningStatistics::add(double x) {
  if (!std::isfinite(x)) throw InputError(fmt::format("value {} is not finite", x));
  ++n_;
  const double d = x - mean_;
  mean_ += d / static_cast<double>(n_);
  m2_ += d * (x - mean_);
  min_ = std::min(min_, x);
  max_ = std::max(max_, x);
}

double RunningStatistics::rms() const noexcept {
  if (n_ == 0) return std::numeric_limits<double>::quiet_NaN();
  return std::sqrt(mean_ * mean_ + m2_ / static_cast<double>(n_));
}

double RunningStatistics::std_dev() const noexcept {
  if (n_ < 2) return std::numeric_limits<double>::quiet_NaN();
  return std::sqrt(m2_ / static_cast<double>(n_ - 1));
}

PointsSummary::PointsSummary(std::size_t sample_capacity) : sample_(sample_capacity) {}

void PointsSummary::add(const GeodeticPoint& p, const FieldValues& v) {
  // Check all three first so the statistics never disagree on the count.
  for (const auto& [x, name] :
       {std::pair{v.xi_rad, "xi_rad"}, {v.eta_rad, "eta_rad"}, {v.geoid_m, "geoid_m"}})
    if (!std::isfinite(x))
      throw InputError(fmt::format("value {} is not finite", x), {"", std::nullopt, name});
  xi_.add(v.xi_rad);
  eta_.add(v.eta_rad);
  geoid_.add(v.geoid_m);
  if (count() == 1) {
    box_ = {p.lat_rad, p.lat_rad, p.lon_rad, p.lon_rad, p.height_m, p.height_m};
  } else {
    box_.lat_min_rad = std::min(box_.lat_min_rad, p.lat_rad);
    box_.lat_max_rad = std::max(box_.lat_max_rad, p.lat_rad);
    box_.lon_min_rad = std::min(box_.lon_min_rad, p.lon_rad);
    box_.lon_max_rad = std::max(box_.lon_max_rad, p.lon_rad);
    box_.height_min_m = std::min(box_.height_min_m, p.height_m);
    box_.height_max_m = std::max(box_.height_max_m, p.height_m);
  }
  sample_.add(p, v);
}

void PointsSummary::add(std::span<const GeodeticPoint> points,
                        std::span<const FieldValues> values) {
  if (points.size() != values.size())
    throw InputError(fmt::format("{} points but {} results", points.size(), values.size()));
  for (std::size_t i = 0; i < points.size(); ++i) add(points[i], values[i]);
}

}  // namespace meridian::gravity
