#pragma once
/// \file gravity_circle.hpp
/// Fast evaluation at many longitudes on one parallel (fixed geodetic
/// latitude and height), like GeographicLib's GravityCircle: the O(N²)
/// Legendre sums are formed once; each longitude then costs O(M).
/// Results are the same quantities, to rounding, as GravityField::evaluate.

#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "meridian/gravity/gravity_field.hpp"

namespace meridian::gravity {

class GravityCircle {
 public:
  /// Precompute for latitude `lat_rad` and height `height_m` (validated as
  /// in GravityField::check_point). `what` selects what later calls return;
  /// Geoid needs a second set of sums at h = 0 (the geoid is defined there).
  GravityCircle(const GravityField& field, double lat_rad, double height_m, Quantities what = Quantities::All);
  ~GravityCircle();
  GravityCircle(GravityCircle&&) noexcept;
  GravityCircle& operator=(GravityCircle&&) noexcept;

  double lat_rad() const noexcept { return lat_rad_; }
  double height_m() const noexcept { return height_m_; }

  /// Values at longitude `lon_rad` (any value). NaN where not requested.
  FieldValues evaluate(double lon_rad) const;
  /// Many longitudes (single thread; cheap per point).
  std::vector<FieldValues> evaluate(std::span<const double> lon_rad) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double lat_rad_ = 0, height_m_ = 0;
};

/// Receives row `row` of evaluate_parallels: the values at every longitude, in order.
using ParallelSink = std::function<void(std::size_t row, std::span<const FieldValues> values)>;

/// The model on the grid `lat_rad` (rows) × `lon_rad` (columns, any values) at one
/// ellipsoidal height: a GravityCircle per row, rows spread over `threads` threads (0 =
/// std::thread::hardware_concurrency(); never more than rows). `sink` gets each row once,
/// from the worker threads and in no particular order (it must accept distinct rows
/// concurrently). Throws as GravityCircle for a bad latitude or height; NumericalError
/// with field "points[i, j]" when ξ, η (Deflection) or N (Geoid) is not finite at row i,
/// column j (a model whose coefficients, GM or radius are out of range); the first error of
/// any thread stops the others and is rethrown, as is whatever the sink throws.
void evaluate_parallels(const GravityField& field, std::span<const double> lat_rad, std::span<const double> lon_rad,
                        double height_m, Quantities what, unsigned threads, const ParallelSink& sink);

}  // namespace meridian::gravity
