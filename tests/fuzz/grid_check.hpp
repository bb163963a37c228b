#pragma once
// A geoid grid a reader accepted is evaluated at its nodes' corners, centre
// and a few fixed places with both interpolations: each answer is a height
// within the physical range (bilinear: |N| ≤ 150 m; bicubic's weights sum in
// absolute value to at most 1.25² = 1.5625) or a meridian::Error.

#include <cmath>
#include <initializer_list>

#include "fuzz_support.hpp"
#include "meridian/gravity/geoid_grid.hpp"
#include "meridian/io/gravity_geoid_grid.hpp"

namespace meridian_fuzz {

inline void check_grid(const meridian::gravity::GeoidGrid& g) {
  namespace gg = meridian::gravity;
  const double lat_a = g.first_lat_rad, lat_b = g.first_lat_rad + (g.rows - 1) * g.dlat_rad;
  const double lon_a = g.first_lon_rad, lon_b = g.first_lon_rad + (g.cols - 1) * g.dlon_rad;
  const double d = 0.0174532925199432958;
  for (const double la : {lat_a, lat_b, 0.5 * (lat_a + lat_b), 0.3 * lat_a + 0.7 * lat_b, 0.0, 1.5,
                          -1.5707963267948966})
    for (const double lo : {lon_a, lon_b, 0.5 * (lon_a + lon_b), 0.8 * lon_a + 0.2 * lon_b,
                            -3.14159, 3.1 + 360 * d, lon_a - 360 * d})
      for (const auto interp : {gg::GridInterpolation::Bilinear, gg::GridInterpolation::Bicubic})
        expect_value_or_error([&] {
          const gg::GridPointResult r = gg::evaluate_grid_point(g, la, lo, interp);
          check_finite(r.geoid_m, "N is NaN or infinite");
          const double bound =
              gg::GeoidGrid::kMaxGeoidHeight_m *
              (r.interpolation_used == gg::GridInterpolation::Bilinear ? 1.0 : 1.5625);
          if (std::abs(r.geoid_m) > bound * (1 + 1e-12)) finding("N outside the physical range");
          if (r.fallback) {
            check_finite(r.fallback->xi_rad, "fallback xi is NaN or infinite");
            check_finite(r.fallback->eta_rad, "fallback eta is NaN or infinite");
          }
        });
}

}  // namespace meridian_fuzz
