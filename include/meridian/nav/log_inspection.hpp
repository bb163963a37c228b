#pragma once
/// \file log_inspection.hpp
/// What an NMEA 0183 log holds and what is wrong with it: the per-file result of
/// `meridian nav inspect` (docs/cli.md), filled by the streaming reader io::nmea::read
/// (io/nmea.hpp) and written by report/nav_inspect.hpp. A plain result: counts, line numbers
/// and times, no file handle.
///
/// Times are seconds since 1970-01-01T00:00:00Z (UTC, no leap seconds, as POSIX time; format
/// them with nav::iso8601_utc, nav/utc_time.hpp); dates are days since 1970-01-01.
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace meridian::nav {

/// Lines whose numbers a LogInspection keeps per problem (the counts are complete).
inline constexpr std::size_t kMaxLinesListed = 10;

/// 1024 GPS weeks in days: a date this much before the logger's stamp is a week rollover.
inline constexpr int kGpsRolloverDays = 7168;

/// What a file holds and what is wrong with it. Counts are complete; line lists keep the first
/// kMaxLinesListed.
struct LogInspection {
  std::string file;
  long lines = 0;                       ///< physical lines
  std::map<std::string, long> sentences;  ///< accepted sentences by talker+type ("INGGA")
  long proprietary = 0;   ///< `$P…`, checksum valid, skipped
  long unknown = 0;       ///< accepted sentences of types not decoded
  long bad_checksum = 0;  ///< rejected
  long no_checksum = 0;   ///< rejected unless accept_missing_checksum
  /// no_checksum by talker+type ("GPVTG"; a line whose address is not 5 letters or digits
  /// counts only in no_checksum; at most 1024 keys).
  std::map<std::string, long> no_checksum_by_type;
  long malformed = 0;     ///< truncated, corrupt, non-ASCII, too few fields, overlong; rejected
  /// A sentence with a time of day (GGA, GLL, RMC, ZDA) byte-identical, logger prefix
  /// included, to the previous one of its talker+type: counted in `sentences` and here, not
  /// delivered (the epoch exists already). Untimed repeats (a steady heading) are ordinary.
  long duplicates = 0;
  std::map<std::string, long> duplicates_by_type;
  long comments = 0, blank = 0;
  long logger_prefixed = 0;  ///< lines with text before the `$`
  bool accept_missing_checksum = false;
  std::vector<int> bad_checksum_lines, no_checksum_lines;
  std::vector<std::pair<int, std::string>> malformed_lines;  ///< line, reason
  /// Earliest and latest time: of the dated sentences when there are any, else of the logger
  /// stamps (time_source "sentences", "logger" or "" when neither exists).
  std::optional<double> first_time_s, last_time_s;
  std::string time_source;
  bool gps_week_rollover_suspected = false;
  std::optional<int> rollover_line;  ///< first date that looks rolled over
  std::optional<std::int64_t> first_date_days;  ///< first RMC/ZDA date
};

}  // namespace meridian::nav
