#include "meridian/io/gravity_points.hpp"

#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "meridian/core/dms.hpp"
#include "meridian/core/error.hpp"

namespace meridian::io {
namespace {

double parse_coordinate(std::string_view text, const char* what, double limit_deg) {
  Angle a = Angle::radians(0);
  try {
    a = parse_angle(text);
  } catch (Error& e) {
    e.add_context("", std::nullopt, what);
    throw;
  }
  if (std::abs(a.deg()) > limit_deg)
    throw InputError(
        fmt::format("{} {} deg is outside [-{}, {}]", what, a.deg(), limit_deg, limit_deg),
        {"", {}, what});
  return a.rad();
}

}  // namespace

double parse_latitude_rad(std::string_view text) { return parse_coordinate(text, "latitude", 90); }

double parse_longitude_rad(std::string_view text) {
  return parse_coordinate(text, "longitude", 540);
}

GravityPointReader::GravityPointReader(std::istream& in, std::string source)
    : records_(in, std::move(source), {Delimiter::Auto, HeaderMode::Auto}) {}

bool GravityPointReader::next(std::vector<gravity::GeodeticPoint>& out, std::size_t max) {
  out.clear();
  if (!records_.next(chunk_, max)) return false;
  if (!height_scale_) {
    // A header's units are applied or refused, never ignored (issue 35: `h [km]` was read as
    // metres): lat and lon in degrees (DMS text or decimal), h in m or km.
    height_scale_ = 1.0;
    const auto& cols = records_.header();
    for (std::size_t c = 0; c < cols.size() && c < 3; ++c) {
      const std::string& u = cols[c].unit;
      if (u.empty()) continue;
      if (c < 2 && (u == "deg" || u == "°" || u == "dms")) continue;
      if (c == 2 && u == "m") continue;
      if (c == 2 && u == "km") {
        height_scale_ = 1000.0;
        continue;
      }
      throw InputError(fmt::format("column {} [{}]: {} (Meridian converts no other unit here)", cols[c].name, u,
                                   c < 2 ? "latitude and longitude are in degrees ([deg], DMS text or decimal)"
                                         : "heights in [m] or [km]"),
                       {records_.source(), records_.header_line(), cols[c].name});
    }
  }
  out.reserve(chunk_.size());
  for (std::size_t i = 0; i < chunk_.size(); ++i) {
    const Record r = chunk_[i];
    if (r.size() < 2 || r.size() > 3)
      throw InputError(fmt::format("expected lat,lon[,h] (2 or 3 fields), got {}", r.size()),
                       r.context());
    gravity::GeodeticPoint p{r.parse(0, parse_latitude_rad), r.parse(1, parse_longitude_rad), 0.0};
    if (r.size() == 3) p.height_m = r.number(2, {"h", "height"}) * *height_scale_;
    try {
      gravity::GravityField::check_point(p);
    } catch (Error& e) {
      e.add_context(r.source(), r.line());
      throw;
    }
    out.push_back(p);
  }
  return true;
}

}  // namespace meridian::io
