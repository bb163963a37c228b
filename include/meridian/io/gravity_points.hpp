#pragma once
/// \file gravity_points.hpp
/// Reading the points of `meridian gravity points` (and the LAT LON of
/// `gravity point`): rows `lat,lon[,h]` of delimited text (record_reader.hpp:
/// `#` comments, blank lines, an optional header line, comma, semicolon or
/// whitespace, CRLF), read a chunk at a time. The columns are taken by
/// position — latitude, longitude, ellipsoidal height — whatever the
/// header calls them; the format is in docs/gravity-field.md.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <istream>
#include <string>
#include <string_view>
#include <vector>

#include "meridian/gravity/gravity_field.hpp"
#include "meridian/io/record_reader.hpp"

namespace meridian::io {

/// A geodetic latitude as a user types it (core/dms.hpp parse_angle:
/// decimal degrees or DMS), in radians. Throws ParseError (unreadable) or
/// InputError (|φ| > 90°), field "latitude".
double parse_latitude_rad(std::string_view text);

/// A longitude, east positive, as above, in radians; |λ| ≤ 540° is accepted
/// (values past ±180° are meaningful and kept as given). Field "longitude".
double parse_longitude_rad(std::string_view text);

/// Streams `lat,lon[,h]` rows into gravity::GeodeticPoint.
class GravityPointReader {
 public:
  /// `source` names the input in errors ("points.csv", "<stdin>").
  GravityPointReader(std::istream& in, std::string source);

  /// Replace `out` with the next points, at most `max` (≥ 1); false when
  /// none were left. Each row has 2 or 3 fields: latitude, longitude
  /// (parse_latitude_rad, parse_longitude_rad) and the ellipsoidal height in
  /// metres (default 0). Every point is checked with
  /// GravityField::check_point. Errors name the source and the line:
  /// `pts.csv:2: longitude: cannot read angle "abc": …`,
  /// `pts.csv:1: expected lat,lon[,h] (2 or 3 fields), got 4`,
  /// `pts.csv:1: h: height "5x" is not a number`.
  bool next(std::vector<gravity::GeodeticPoint>& out, std::size_t max);

  /// Bytes of the input consumed so far (for progress).
  std::uint64_t bytes_read() const noexcept { return records_.bytes_read(); }

 private:
  RecordReader records_;
  RecordChunk chunk_;
  std::optional<double> height_scale_{};  // the h column's header unit to metres, once read
};

}  // namespace meridian::io
