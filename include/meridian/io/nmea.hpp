#pragma once
/// \file nmea.hpp
/// A streaming NMEA 0183 reader (docs/file-formats.md, "NMEA 0183") that also fills the
/// whole-file inspection summary behind `meridian nav inspect` (nav::LogInspection).
///
/// Lines: `$TTSSS,f1,f2,…*HH` with an optional logger prefix before the `$` (e.g.
/// `2014-08-01T00:00:00.285000Z $INGGA,…`; an ISO 8601 UTC prefix is exposed as
/// Sentence::logger_time_s), CR LF or LF, no final newline needed, `#` comment lines and blank
/// lines skipped. TT is any talker ID, SSS the type; `$P…` sentences are proprietary. The
/// checksum HH (upper or lower case hex) is the XOR of the bytes between `$` and `*`
/// (NMEA 0183 v4.11 §5.2.1). Memory is constant: a line longer than kMaxLineBytes is
/// malformed and not stored.
///
/// Decoded: GGA, HDT, VTG, VBW, RMC, ZDA, GLL (also the NMEA 1.x GLL without time and
/// status, and the 1.x VTG without unit letters). Units: angles in radians (latitude north
/// positive, longitude east positive, heading and course clockwise from true north in
/// [0, 2π)), speeds in m/s (1 kn = 1852/3600 m/s, 1 km/h = 1/3.6 m/s), heights in metres,
/// times in seconds: time of day since 00:00 UTC, absolute times as seconds since
/// 1970-01-01T00:00:00Z (UTC, no leap seconds, as POSIX time). An empty field is std::nullopt,
/// never 0.
///
/// Dates: RMC and ZDA carry a date; the latest one dates the GGA, GLL and RMC/ZDA times that
/// follow (Sentence::time_s): the time of day is put on the day that makes it nearest to the
/// last dated instant, so fixes that straddle midnight get increasing times.
///
/// Errors: IoError naming the file when it cannot be opened or read. Nothing in the content
/// is fatal: bad checksums, missing checksums, malformed and overlong lines are counted with
/// their line numbers (Summary) and not delivered; so are duplicates (Summary::duplicates).

#include <cstdint>
#include <functional>
#include <istream>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "meridian/nav/log_inspection.hpp"
#include "meridian/nav/utc_time.hpp"

namespace meridian::io::nmea {

/// Longest line read (bytes, without the line end); NMEA 0183 allows 82, loggers add a prefix.
inline constexpr std::size_t kMaxLineBytes = 4096;

/// The limits of the summary (nav/log_inspection.hpp).
using nav::kGpsRolloverDays;
using nav::kMaxLinesListed;

/// GGA: fix data.
struct Gga {
  std::optional<double> time_of_day_s;
  std::optional<double> lat_rad, lon_rad;
  std::optional<int> fix_quality;  ///< 0 invalid, 1 GPS, 2 DGPS, 4 RTK fixed, 5 RTK float, 6 DR
  std::optional<int> satellites;
  std::optional<double> hdop;
  std::optional<double> altitude_m;  ///< antenna height above mean sea level (geoid)
};

/// HDT: true heading.
struct Hdt {
  std::optional<double> heading_rad;
};

/// VTG: course and speed over ground.
struct Vtg {
  std::optional<double> course_true_rad;
  std::optional<double> speed_m_s;  ///< from the knots field, else the km/h field
};

/// VBW: dual ground/water speed; longitudinal positive forward, transverse positive starboard.
struct Vbw {
  std::optional<double> water_longitudinal_m_s, water_transverse_m_s;
  std::optional<bool> water_valid;  ///< status A (true) / V (false)
  std::optional<double> ground_longitudinal_m_s, ground_transverse_m_s;
  std::optional<bool> ground_valid;
};

/// RMC: recommended minimum data.
struct Rmc {
  std::optional<double> time_of_day_s;
  std::optional<bool> valid;  ///< status A / V
  std::optional<double> lat_rad, lon_rad;
  std::optional<double> speed_m_s, course_true_rad;
  std::optional<std::int64_t> date_days;  ///< days since 1970-01-01 (two-digit years: 19xx ≥ 80)
};

/// ZDA: time and date.
struct Zda {
  std::optional<double> time_of_day_s;
  std::optional<std::int64_t> date_days;  ///< days since 1970-01-01
};

/// GLL: geographic position (NMEA 1.x: latitude and longitude only).
struct Gll {
  std::optional<double> lat_rad, lon_rad;
  std::optional<double> time_of_day_s;
  std::optional<bool> valid;
};

/// The decoded content; std::monostate for a valid sentence of a type not decoded here.
using Data = std::variant<std::monostate, Gga, Hdt, Vtg, Vbw, Rmc, Zda, Gll>;

/// One accepted sentence.
struct Sentence {
  int line = 0;              ///< 1-based line in the file
  std::string talker;        ///< e.g. "IN", "HE"
  std::string type;          ///< e.g. "GGA"
  std::optional<double> logger_time_s;  ///< the logger prefix, when it is an ISO 8601 time
  std::optional<double> time_s;         ///< absolute UTC time when a date is known
  bool has_checksum = true;  ///< false: accepted under accept_missing_checksum
  Data data;
};

struct Options {
  /// Accept sentences without `*HH` (counted, with a warning in the summary); default: reject.
  bool accept_missing_checksum = false;
};

/// What a file holds and what is wrong with it: a plain result of the nav module, so that its
/// writers (report/nav_inspect.hpp) need no io.
using Summary = nav::LogInspection;

/// The calendar arithmetic of the reader (nav/utc_time.hpp).
using nav::days_from_civil;
using nav::iso8601_utc;

/// Read `in` line by line, calling `on_sentence` for each accepted sentence; `source` names
/// the file in the summary. Never throws for content, but for a line longer than 1 MiB
/// (ParseError "line N is longer than 1 MiB: not a text file?"); IoError when the stream goes bad.
Summary read(std::istream& in, const std::string& source, const Options& options,
             const std::function<void(const Sentence&)>& on_sentence);
/// read() of the file at `path`; IoError naming it when it cannot be opened.
Summary read_file(const std::string& path, const Options& options,
                  const std::function<void(const Sentence&)>& on_sentence = {});

/// The runner of `nav inspect`: the summary of every file in order, all read before any is
/// returned (an unreadable one fails the whole run: IoError naming it).
std::vector<Summary> inspect_files(const std::vector<std::string>& paths, bool accept_missing_checksum);

}  // namespace meridian::io::nmea
