#include "meridian/report/nav_inspect.hpp"

#include <fmt/format.h>

#include "meridian/nav/utc_time.hpp"

namespace meridian::report {
namespace {

nlohmann::json nav_time_or_null(const std::optional<double>& t) {
  return t ? nlohmann::json(nav::iso8601_utc(*t)) : nlohmann::json();
}

std::vector<std::string> nav_warnings(const nav::LogInspection& s) {
  std::vector<std::string> w;
  long accepted = 0;
  for (const auto& [key, n] : s.sentences) accepted += n;
  if (accepted == 0 && s.proprietary == 0)
    w.push_back(s.lines == 0 ? std::string("the file is empty: no NMEA sentence")
                             : fmt::format("no valid NMEA sentence in {} line{}", s.lines, s.lines == 1 ? "" : "s"));
  if (s.gps_week_rollover_suspected)
    w.push_back(fmt::format("dates look like a GPS week rollover (1024 weeks early), first at line {}; "
                            "sentence times are as logged",
                            s.rollover_line.value_or(0)));
  if (s.accept_missing_checksum && s.no_checksum > 0)
    w.push_back(fmt::format("{} sentence{} without a checksum accepted unverified", s.no_checksum,
                            s.no_checksum == 1 ? "" : "s"));
  if (s.no_checksum > 0 && !s.accept_missing_checksum)
    w.push_back(fmt::format("{} sentence{} without a checksum rejected (--accept-missing-checksum accepts them)",
                            s.no_checksum, s.no_checksum == 1 ? "" : "s"));
  return w;
}

std::string nav_line_list(const std::vector<int>& lines, long total) {
  std::string out = fmt::format("{}", fmt::join(lines, ", "));
  if (total > static_cast<long>(lines.size())) out += ", …";
  return out;
}

}  // namespace

nlohmann::json nav_inspect_to_json(const nav::LogInspection& s) {
  nlohmann::json j;
  j["file"] = s.file;
  j["lines"] = s.lines;
  j["sentences"] = nlohmann::json(s.sentences);  // a std::map becomes an object, {} when empty
  j["proprietary"] = s.proprietary;
  j["unknown"] = s.unknown;
  j["bad_checksum"] = s.bad_checksum;
  j["no_checksum"] = s.no_checksum;
  j["malformed"] = s.malformed;
  j["duplicates"] = s.duplicates;
  j["duplicates_by_type"] = nlohmann::json(s.duplicates_by_type);
  j["comments"] = s.comments;
  j["logger_prefixed"] = s.logger_prefixed;
  j["accept_missing_checksum"] = s.accept_missing_checksum;
  j["first_time"] = nav_time_or_null(s.first_time_s);
  j["last_time"] = nav_time_or_null(s.last_time_s);
  j["time_source"] = s.time_source.empty() ? nlohmann::json() : nlohmann::json(s.time_source);
  j["first_date"] = s.first_date_days
                        ? nlohmann::json(nav::iso8601_utc(static_cast<double>(*s.first_date_days) * 86400.0)
                                             .substr(0, 10))
                        : nlohmann::json();
  j["gps_week_rollover_suspected"] = s.gps_week_rollover_suspected;
  j["rollover_line"] = s.rollover_line ? nlohmann::json(*s.rollover_line) : nlohmann::json();
  j["bad_checksum_lines"] = s.bad_checksum_lines;
  j["no_checksum_lines"] = s.no_checksum_lines;
  j["malformed_lines"] = nlohmann::json::array();
  for (const auto& [line, reason] : s.malformed_lines)
    j["malformed_lines"].push_back({{"line", line}, {"reason", reason}});
  j["warnings"] = nav_warnings(s);
  return j;
}

nlohmann::json nav_inspect_files_to_json(const std::vector<nav::LogInspection>& summaries) {
  nlohmann::json files = nlohmann::json::array();
  for (const nav::LogInspection& s : summaries) files.push_back(nav_inspect_to_json(s));
  return nlohmann::json{{"files", files}};
}

std::string nav_inspect_text(const std::vector<nav::LogInspection>& summaries) {
  std::string text;
  for (std::size_t k = 0; k < summaries.size(); ++k) text += (k ? "\n" : "") + nav_inspect_text(summaries[k]);
  return text;
}

std::string nav_inspect_text(const nav::LogInspection& s) {
  std::string out = fmt::format("{}: {} lines\n", s.file, s.lines);
  long accepted = 0;
  for (const auto& [k, n] : s.sentences) accepted += n;
  out += fmt::format("  sentences accepted: {}\n", accepted);
  for (const auto& [k, n] : s.sentences) {
    const auto d = s.duplicates_by_type.find(k);
    out += fmt::format("    {:<8} {:>8}", k, n);
    if (d != s.duplicates_by_type.end()) out += fmt::format("  ({} exact repeats)", d->second);
    out += "\n";
  }
  out += fmt::format("  proprietary skipped: {}   types not decoded: {}   comments: {}   logger-stamped: {}\n",
                     s.proprietary, s.unknown, s.comments, s.logger_prefixed);
  out += fmt::format("  bad checksum: {}", s.bad_checksum);
  if (s.bad_checksum > 0) out += fmt::format(" (lines {})", nav_line_list(s.bad_checksum_lines, s.bad_checksum));
  out += fmt::format("\n  no checksum: {}{}", s.no_checksum, s.accept_missing_checksum ? " (accepted)" : "");
  if (s.no_checksum > 0) out += fmt::format(" (lines {})", nav_line_list(s.no_checksum_lines, s.no_checksum));
  out += fmt::format("\n  malformed: {}\n", s.malformed);
  for (const auto& [line, reason] : s.malformed_lines) out += fmt::format("    line {}: {}\n", line, reason);
  out += fmt::format("  duplicates: {}\n", s.duplicates);
  if (s.first_time_s)
    out += fmt::format("  time: {} to {} ({})\n", nav::iso8601_utc(*s.first_time_s),
                       nav::iso8601_utc(*s.last_time_s), s.time_source == "logger" ? "logger stamps" : "sentences");
  else
    out += "  time: none (no dated sentence was accepted and no line has a logger stamp)\n";
  for (const auto& w : nav_warnings(s)) out += fmt::format("  warning: {}\n", w);
  return out;
}

}  // namespace meridian::report
