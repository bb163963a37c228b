#include "meridian/gravity/thinned_sample.hpp"

#include <algorithm>

namespace meridian::gravity {

ThinnedSample::ThinnedSample(std::size_t capacity) : capacity_(std::max<std::size_t>(capacity, 1)) {
  points_.reserve(capacity_);
}

void ThinnedSample::add(const GeodeticPoint& p, const FieldValues& v) {
  const std::uint64_t i = seen_++;
  if (i % stride_ != 0) return;
  // Full: double the stride and keep the points at multiples of it (every
  // second one, the first included); then the new point is kept only if it
  // is at a multiple of the new stride too.
  while (points_.size() >= capacity_) {
    stride_ *= 2;
    std::erase_if(points_, [&](const SamplePoint& s) { return s.index % stride_ != 0; });
    if (i % stride_ != 0) return;
  }
  points_.push_back({i, p.lat_rad, p.lon_rad, p.height_m, v.xi_rad, v.eta_rad, v.geoid_m});
}

}  // namespace meridian::gravity
