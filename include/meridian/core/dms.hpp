#pragma once
/// \file dms.hpp
/// Parsing and formatting of sexagesimal notation as surveyors write it:
/// angles (D°M′S″, calculator DDD.MMSS, gon) and stopwatch times (m:ss.s).

#include <string>
#include <string_view>

#include "meridian/core/angle.hpp"

namespace meridian {

/// Parse an angle written as
/// * degrees-minutes-seconds with symbols: `157°21'00"`, `157°21′00.5″`,
///   `157d21m00s`, or colons `157:21:00`;
/// * space-separated D M S or D M: `157 21 00`, `-0 01 16.2`, `157 21.5`;
/// * decimal degrees: `157.35`, `-0.0045`, optionally with `°` or `deg`, or with an exponent
///   `4.98e-05`, `-1E-3` (no marker then);
/// * gon: `174.8333g`, `174.8333 gon`;
/// * radians: `2.746 rad`;
/// * arc-seconds or arc-minutes: `93.6"`, `12.5'` (single component with symbol).
/// A leading sign applies to the whole angle. Minutes and seconds of a
/// multi-component angle must lie in [0, 60); the components after the
/// first must be non-negative. Throws ParseError naming the text otherwise
/// (including NaN, infinity, empty text and trailing garbage).
Angle parse_angle(std::string_view text);

/// How a field book writes the angles read on the horizontal circle: the
/// `angle_unit:` of a gyro file (docs/file-formats.md). Always stated by the
/// file, never guessed from the values (123.4530 is a valid angle in every
/// unit, and means three different directions).
enum class AngleUnit {
  Dms,      ///< "dms", the default: a number is decimal degrees, text any form of parse_angle(text)
  Degrees,  ///< "deg": decimal degrees, number or text ("157.35", "157.35°", "157.35 deg")
  Gon,      ///< "gon": decimal gon, 400 gon to the circle ("174.8333", "174.8333 gon", "174.8333g")
  DddMmss,  ///< "ddd.mmss": calculator notation, 123.4530 = 123°45′30″ (parse_ddd_mmss)
};

/// The unit named as in a file: "dms", "deg", "gon" or "ddd.mmss".
/// Throws ParseError naming the accepted names otherwise.
AngleUnit angle_unit_from_string(std::string_view name);
/// The file name of a unit: "dms", "deg", "gon", "ddd.mmss".
std::string to_string(AngleUnit unit);

/// Parse an angle written in a field book's unit (`text` is the value as
/// written: a YAML number's own digits, or a string).
/// * Dms: parse_angle(text) — unchanged behaviour of files without angle_unit;
/// * Degrees, Gon: a plain decimal number with an optional sign, optionally
///   followed by the unit's own mark (°/deg, gon/g); any other notation
///   (D M S, another unit's mark, exponents) is rejected rather than
///   reinterpreted;
/// * DddMmss: parse_ddd_mmss(text).
/// Throws ParseError naming the text and the unit.
Angle parse_angle(std::string_view text, AngleUnit unit);

/// Parse calculator notation DDD.MMSSs…: the digits after the point are two
/// of minutes, two of seconds, then decimals of seconds, so 123.4530 is
/// 123°45′30″, 123.45305 is 123°45′30.5″, 123.45 is 123°45′00″ and 123 is
/// 123°00′00″ (the →HMS convention of surveying calculators). A leading
/// sign applies to the whole angle: -0.0116 is −0°01′16″.
/// Throws ParseError when minutes or seconds are not below 60 (123.4599:
/// probably decimal degrees booked in the wrong unit), when one or three
/// digits follow the point (123.4 and 123.453 do not say which digit is
/// the tens of minutes or of seconds), and for anything but digits, one
/// point and a leading sign.
Angle parse_ddd_mmss(std::string_view text);

/// Format as DDD.MMSS with `second_decimals` (0…6) further digits of seconds,
/// rounding carried into minutes and degrees: 123°45′30.5″ with 1 gives
/// "123.45305". Negative angles get a leading '-'; non-finite values print
/// "nan"/"inf". parse_ddd_mmss reads the result back (to the last digit).
std::string format_ddd_mmss(Angle a, int second_decimals = 1);

/// Parse a stopwatch reading to seconds:
/// * `m:ss` or `m:ss.s…` (4:07.3 = 247.3 s; minutes may exceed 59);
/// * `h:mm:ss` or `h:mm:ss.s…` (1:02:03.5 = 3723.5 s);
/// * `m′ss.s″` or `m'ss.s"` as booked by hand (the seconds mark optional);
/// * a plain unsigned decimal number of seconds (`279.6`).
/// Seconds (and the minutes of h:mm:ss) are written with two digits and
/// must be below 60; only the last part may have decimals. Throws
/// ParseError naming the text for a sign, seconds ≥ 60, a one-digit
/// seconds field (4:7.3), empty parts or anything else.
double parse_stopwatch_s(std::string_view text);

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
