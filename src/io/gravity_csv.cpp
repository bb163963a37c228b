#include "meridian/io/gravity_csv.hpp"

#include <iterator>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"

namespace meridian::io {

std::string_view gravity_points_csv_header() noexcept {
  return "lat_deg,lon_deg,h_m,xi_arcsec,eta_arcsec,geoid_m\n";
}

void append_gravity_points_csv(std::string& out, std::span<const gravity::GeodeticPoint> points,
                               std::span<const gravity::FieldValues> values) {
  if (points.size() != values.size())
    throw InputError(fmt::format("{} points but {} results", points.size(), values.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
    fmt::format_to(std::back_inserter(out), "{:.10f},{:.10f},{:.4f},{:.9f},{:.9f},{:.9f}\n",
                   units::rad_to_deg(points[i].lat_rad), units::rad_to_deg(points[i].lon_rad),
                   points[i].height_m, units::rad_to_arcsec(values[i].xi_rad),
                   units::rad_to_arcsec(values[i].eta_rad), values[i].geoid_m);
}

}  // namespace meridian::io
