#pragma once
/// \file thinned_sample.hpp
/// A bounded, deterministic sample of a stream of evaluated points, spread
/// evenly over the whole stream, for maps of runs too long to draw point by
/// point.
///
/// Rule: the sample holds exactly the points whose 0-based position i in
/// the stream is a multiple of the stride k, where k is the smallest power
/// of two with ⌈n/k⌉ ≤ capacity (n = points seen). It is kept while
/// streaming: every k-th point is appended; when the sample is full and
/// another is due, k doubles and every second kept point is dropped. So the
/// sample never exceeds `capacity`, holds more than capacity/2 points once
/// n ≥ capacity, starts at the first point, ends within k points of the
/// last, and depends only on n and capacity (not on chunking).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "meridian/gravity/gravity_field.hpp"

namespace meridian::gravity {

/// One kept point: where, and the quantities the maps show.
struct SamplePoint {
  std::uint64_t index = 0;  ///< 0-based position in the stream
  double lat_rad = 0, lon_rad = 0, height_m = 0;
  double xi_rad = 0, eta_rad = 0, geoid_m = 0;
};

class ThinnedSample {
 public:
  /// At most `capacity` points (≥ 1; 0 is taken as 1).
  explicit ThinnedSample(std::size_t capacity);

  /// Offer the next point of the stream.
  void add(const GeodeticPoint& p, const FieldValues& v);

  /// The kept points, in stream order.
  const std::vector<SamplePoint>& points() const noexcept { return points_; }
  std::size_t capacity() const noexcept { return capacity_; }
  /// The current stride k (a power of two).
  std::uint64_t stride() const noexcept { return stride_; }
  /// Points offered so far (n).
  std::uint64_t seen() const noexcept { return seen_; }

 private:
  std::size_t capacity_;
  std::uint64_t stride_ = 1;
  std::uint64_t seen_ = 0;
  std::vector<SamplePoint> points_;
};

}  // namespace meridian::gravity
