#pragma once
/// \file dms.hpp
/// Parsing and formatting of angles as surveyors write them.

#include <string>
#include <string_view>

#include "meridian/core/angle.hpp"

namespace meridian {

/// Parse an angle written as
/// * degrees-minutes-seconds with symbols: `157°21'00"`, `157°21′00.5″`,
///   `157d21m00s`, or colons `157:21:00`;
/// * space-separated D M S or D M: `157 21 00`, `-0 01 16.2`, `157 21.5`;
/// * decimal degrees: `157.35`, `-0.0045`, optionally with `°` or `deg`;
/// * gon: `174.8333g`, `174.8333 gon`;
/// * radians: `2.746 rad`;
/// * arc-seconds or arc-minutes: `93.6"`, `12.5'` (single component with symbol).
/// A leading sign applies to the whole angle. Minutes and seconds of a
/// multi-component angle must lie in [0, 60); the components after the
/// first must be non-negative. Throws ParseError naming the text otherwise
/// (including NaN, infinity, empty text and trailing garbage).
Angle parse_angle(std::string_view text);

/// Formatting options for DMS output.
struct DmsFormat {
  int second_decimals = 1;     ///< digits after the decimal point of seconds
  bool symbols = true;         ///< `157°21'00.0"` (true) or `157 21 00.0` (false)
  bool force_sign = false;     ///< print `+` for positive values
};

/// Format as signed D°M'S" (rounding carried into minutes and degrees).
/// Non-finite values are printed as "nan"/"inf".
std::string format_dms(Angle a, const DmsFormat& fmt = {});

/// Format a direction normalised to [0°, 360°) as D°M'S".
std::string format_direction_dms(Angle a, const DmsFormat& fmt = {});

}  // namespace meridian
