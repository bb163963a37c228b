#pragma once
/// \file points_summary.hpp
/// Summary statistics of a `gravity points` run, accumulated over the whole
/// stream in constant memory: the number of points; minimum, maximum, mean,
/// RMS and standard deviation of ξ, η and N; the bounding box; and a thinned
/// sample for maps (thinned_sample.hpp).

#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>

#include "meridian/gravity/gravity_field.hpp"
#include "meridian/gravity/thinned_sample.hpp"

namespace meridian::gravity {

/// Count, extremes, mean, RMS and standard deviation of one quantity, one
/// value at a time. The mean and the sum of squared deviations are updated
/// by Welford's recurrence (Welford 1962; Knuth, TAOCP 2, §4.2.2), which
/// does not lose precision when the spread is small beside the mean (N of
/// tens of metres varying by millimetres).
class RunningStatistics {
 public:
  /// Add one value. Throws InputError for a non-finite value.
  void add(double x);

  std::uint64_t count() const noexcept { return n_; }
  /// Smallest and largest value; NaN when count() is 0.
  double min() const noexcept { return n_ ? min_ : std::numeric_limits<double>::quiet_NaN(); }
  double max() const noexcept { return n_ ? max_ : std::numeric_limits<double>::quiet_NaN(); }
  /// Arithmetic mean; NaN when count() is 0.
  double mean() const noexcept { return n_ ? mean_ : std::numeric_limits<double>::quiet_NaN(); }
  /// Root mean square sqrt(Σx²/n) = sqrt(mean² + m2/n); NaN when count() is 0.
  double rms() const noexcept;
  /// Sample standard deviation sqrt(Σ(x − mean)²/(n − 1)); NaN (not
  /// stated) when count() < 2.
  double std_dev() const noexcept;

 private:
  std::uint64_t n_ = 0;
  double mean_ = 0, m2_ = 0;
  double min_ = std::numeric_limits<double>::infinity(),
         max_ = -std::numeric_limits<double>::infinity();
};

/// Extent of the points (geodetic latitude and longitude as given, height).
/// NaN members when no point was added. Longitudes are compared as given:
/// a run crossing ±180° reports a box spanning the other way round.
struct BoundingBox {
  double lat_min_rad = std::numeric_limits<double>::quiet_NaN(), lat_max_rad = lat_min_rad;
  double lon_min_rad = lat_min_rad, lon_max_rad = lat_min_rad;
  double height_min_m = lat_min_rad, height_max_m = lat_min_rad;
};

class PointsSummary {
 public:
  /// Maps of at most this many points: 3 maps of 5 000 points keep an HTML
  /// report near 1 MB and render in a browser in about a second.
  static constexpr std::size_t kDefaultSampleCapacity = 5000;

  explicit PointsSummary(std::size_t sample_capacity = kDefaultSampleCapacity);

  /// Add one evaluated point. Throws InputError when ξ, η or N is not finite.
  void add(const GeodeticPoint& p, const FieldValues& v);
  /// Add a chunk; `values[i]` belongs to `points[i]`. Throws InputError when
  /// the sizes differ.
  void add(std::span<const GeodeticPoint> points, std::span<const FieldValues> values);

  std::uint64_t count() const noexcept { return xi_.count(); }
  const RunningStatistics& xi_rad() const noexcept { return xi_; }      ///< ξ, rad
  const RunningStatistics& eta_rad() const noexcept { return eta_; }    ///< η, rad
  const RunningStatistics& geoid_m() const noexcept { return geoid_; }  ///< N, m
  const BoundingBox& bounds() const noexcept { return box_; }
  const ThinnedSample& sample() const noexcept { return sample_; }

 private:
  RunningStatistics xi_, eta_, geoid_;
  BoundingBox box_;
  ThinnedSample sample_;
};

}  // namespace meridian::gravity
