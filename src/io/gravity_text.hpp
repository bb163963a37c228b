#pragma once
// Private helpers of the gravity model and geoid grid readers (io_gravity): whole files, blank-
// separated tokens, numbers with Fortran exponents, lower case. One home, so that the readers,
// built as one unity batch, share them instead of defining file-local copies.

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "input_limits.hpp"

namespace meridian::io::detail {

/// The bytes of `path`. Throws IoError for a directory or a device (check_readable_path), "cannot open <what>" or "error reading <what>" naming it.
inline std::string read_whole_file(const std::filesystem::path& path, std::string_view what) {
  check_readable_path(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot open " + std::string(what), {path.string(), {}, ""});
  std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw IoError("error reading " + std::string(what), {path.string(), {}, ""});
  return s;
}

/// Meridian's plausible ranges of a terrestrial gravity model's constants (docs/reliability.md,
/// "Model constants"): its own choice, for models of the Earth only. GM of the Earth is
/// 3.986004418e14 m^3/s^2 and its equatorial radius 6378137 m; a value outside these ranges
/// is a damaged file, a unit slip (a radius in km) or a model of another body.
inline constexpr double kMinModelGm = 3.5e14, kMaxModelGm = 4.5e14;    // m^3/s^2
inline constexpr double kMinModelRadius = 6.0e6, kMaxModelRadius = 6.6e6;  // m
inline constexpr double kMaxModelFlattening = 0.01;

/// Throws ParseError at {file, line, field} unless kMinModelGm <= gm <= kMaxModelGm.
inline void check_model_gm(double gm, const std::string& file, std::optional<int> line, const std::string& field) {
  if (gm >= kMinModelGm && gm <= kMaxModelGm) return;
  throw ParseError(fmt::format("{} = {} m^3/s^2 is not the GM of a terrestrial model (Meridian accepts {:g} to "
                               "{:g} m^3/s^2; the Earth's is 3.986e14)",
                               field, gm, kMinModelGm, kMaxModelGm),
                   {file, line, field});
}

/// Throws ParseError at {file, line, field} unless kMinModelRadius <= r <= kMaxModelRadius,
/// naming a value in kilometres as such.
inline void check_model_radius(double r, const std::string& file, std::optional<int> line, const std::string& field) {
  if (r >= kMinModelRadius && r <= kMaxModelRadius) return;
  if (r >= kMinModelRadius / 1000 && r <= kMaxModelRadius / 1000)
    throw ParseError(fmt::format("{} = {} is a radius in kilometres: the file must give metres ({} m)", field, r,
                                 r * 1000),
                     {file, line, field});
  throw ParseError(fmt::format("{} = {} m is not the radius of a terrestrial model (Meridian accepts {:g} to {:g} m; "
                               "the Earth's equatorial radius is 6378137 m)",
                               field, r, kMinModelRadius, kMaxModelRadius),
                   {file, line, field});
}

/// Throws ParseError at {file, line, field} unless 0 <= f <= kMaxModelFlattening.
inline void check_model_flattening(double f, const std::string& file, std::optional<int> line,
                                   const std::string& field) {
  if (f >= 0 && f <= kMaxModelFlattening) return;
  throw ParseError(fmt::format("{} = {} is not the flattening of a terrestrial model (Meridian accepts 0 to {:g}; "
                               "the Earth's is 1/298.257 = 0.00335)",
                               field, f, kMaxModelFlattening),
                   {file, line, field});
}

/// `s` in ASCII lower case.
inline std::string lower(std::string_view s) {
  std::string r(s);
  std::transform(r.begin(), r.end(), r.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return r;
}

/// Split on blanks (spaces, tabs, CR).
inline void split_fields(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t j = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > j) out.push_back(line.substr(j, i - j));
  }
}

/// A double, accepting Fortran exponents (1.0d0, 1.0D-3). Nullopt if the
/// whole token is not a number.
inline std::optional<double> parse_double(std::string_view tok) {
  char buf[64];
  if (tok.empty() || tok.size() >= sizeof buf) return std::nullopt;
  for (std::size_t i = 0; i < tok.size(); ++i) buf[i] = (tok[i] == 'd' || tok[i] == 'D') ? 'e' : tok[i];
  const char* b = buf;
  const char* e = buf + tok.size();
  if (*b == '+') ++b;
  double v = 0;
  const auto r = std::from_chars(b, e, v);
  if (r.ec != std::errc() || r.ptr != e) return std::nullopt;
  return v;
}

inline std::optional<int> parse_int(std::string_view tok) {
  int v = 0;
  const auto r = std::from_chars(tok.data(), tok.data() + tok.size(), v);
  if (r.ec != std::errc() || r.ptr != tok.data() + tok.size()) return std::nullopt;
  return v;
}

}  // namespace meridian::io::detail
