#pragma once
/// \file nav_inspect.hpp
/// Outputs of `meridian nav inspect` (docs/cli.md): the per-file summary of an NMEA 0183 log
/// (nav/log_inspection.hpp, filled by io/nmea.hpp) as text for a hydrographer and as JSON.
///
/// JSON keys (one object per file): file, lines, sentences {talker+type: count}, proprietary,
/// unknown, bad_checksum, no_checksum, malformed, duplicates, duplicates_by_type, comments,
/// logger_prefixed, accept_missing_checksum, first_time, last_time (ISO 8601 UTC or null),
/// time_source ("sentences", "logger" or null), first_date (YYYY-MM-DD or null),
/// gps_week_rollover_suspected, rollover_line (or null), bad_checksum_lines, no_checksum_lines,
/// malformed_lines [{line, reason}] (the first nav::kMaxLinesListed of each), warnings.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "meridian/nav/log_inspection.hpp"

namespace meridian::report {

/// The JSON object of one file's summary (keys above).
nlohmann::json nav_inspect_to_json(const nav::LogInspection& summary);

/// `nav inspect --json` of several files: {"files": [one object per file, in order]}.
nlohmann::json nav_inspect_files_to_json(const std::vector<nav::LogInspection>& summaries);

/// A text block: counts by sentence, the problems with their first lines, the time span and
/// the warnings (rollover, accepted lines without checksum).
std::string nav_inspect_text(const nav::LogInspection& summary);

/// The text blocks of several files, in order, a blank line between two.
std::string nav_inspect_text(const std::vector<nav::LogInspection>& summaries);

}  // namespace meridian::report
