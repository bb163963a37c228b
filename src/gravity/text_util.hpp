#pragma once
// Private helpers shared by the text readers.

#include <cctype>
#include <charconv>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace meridian::gravity::detail {

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

}  // namespace meridian::gravity::detail
