#include "meridian/core/dms.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian {
namespace {

[[noreturn]] void fail(std::string_view text, const std::string& why) {
  throw ParseError(fmt::format("cannot read angle \"{}\": {}", text, why));
}

// A number token followed by an optional unit marker.
struct Token {
  double value = 0;
  std::string unit;  // "", "d", "m", "s", "g", "rad"
  bool has_fraction = false;
};

bool starts_with(std::string_view s, std::string_view p) { return s.substr(0, p.size()) == p; }

// Unit marker at the start of s; returns its length (0 if none).
std::size_t read_unit(std::string_view s, std::string& unit) {
  struct M { std::string_view text; const char* unit; };
  static constexpr M markers[] = {
      {"\xC2\xB0", "d"},      // °
      {"\xE2\x80\xB2", "m"},  // ′
      {"\xE2\x80\xB3", "s"},  // ″
      {"''", "s"},  {"\"", "s"}, {"'", "m"}, {"deg", "d"}, {"gon", "g"}, {"rad", "rad"},
      {"d", "d"},   {"m", "m"},  {"s", "s"}, {"g", "g"},   {":", ":"},
  };
  for (const auto& m : markers) {
    if (starts_with(s, m.text)) {
      unit = m.unit;
      return m.text.size();
    }
  }
  return 0;
}

}  // namespace

Angle parse_angle(std::string_view text) {
  std::string_view s = text;
  auto skip_ws = [&] {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  };
  skip_ws();
  if (s.empty()) fail(text, "empty");
  double sign = 1.0;
  if (s.front() == '-' || s.front() == '+') {
    if (s.front() == '-') sign = -1.0;
    s.remove_prefix(1);
    skip_ws();
  }
  std::vector<Token> tokens;
  bool colon_form = false;
  while (true) {
    skip_ws();
    if (s.empty()) break;
    if (!(std::isdigit(static_cast<unsigned char>(s.front())) || s.front() == '.'))
      fail(text, fmt::format("unexpected \"{}\"", s.substr(0, 8)));
    // from_chars accepts neither sign nor inf/nan here because we only start at a digit.
    double v = 0;
    const char* b = s.data();
    const char* e = s.data() + s.size();
    auto [ptr, ec] = std::from_chars(b, e, v, std::chars_format::fixed);
    if (ec != std::errc() || ptr == b) fail(text, "bad number");
    Token t;
    t.value = v;
    t.has_fraction = std::string_view(b, static_cast<std::size_t>(ptr - b)).find('.') != std::string_view::npos;
    s.remove_prefix(static_cast<std::size_t>(ptr - b));
    skip_ws();
    std::size_t n = read_unit(s, t.unit);
    if (t.unit == ":") {
      colon_form = true;
      t.unit.clear();
    }
    s.remove_prefix(n);
    tokens.push_back(t);
    if (tokens.size() > 3) fail(text, "more than three components");
  }
  if (tokens.empty()) fail(text, "no number");
  for (const auto& t : tokens)
    if (!std::isfinite(t.value)) fail(text, "not a finite number");

  if (tokens.size() == 1) {
    const Token& t = tokens[0];
    if (colon_form) fail(text, "dangling ':'");
    if (t.unit.empty() || t.unit == "d") return Angle::degrees(sign * t.value);
    if (t.unit == "m") return Angle::arcminutes(sign * t.value);
    if (t.unit == "s") return Angle::arcseconds(sign * t.value);
    if (t.unit == "g") return Angle::gon(sign * t.value);
    if (t.unit == "rad") return Angle::radians(sign * t.value);
    fail(text, "unknown unit");
  }
  // Multi-component: D M [S]. Units, where written, must be d, m, s in order.
  static const char* expected[] = {"d", "m", "s"};
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    if (!tokens[i].unit.empty() && tokens[i].unit != expected[i])
      fail(text, "components must be degrees, minutes, seconds in that order");
    if (i + 1 < tokens.size() && tokens[i].has_fraction)
      fail(text, "only the last component may have a fraction");
  }
  const double d = tokens[0].value;
  const double m = tokens[1].value;
  const double sec = tokens.size() > 2 ? tokens[2].value : 0.0;
  if (m >= 60.0) fail(text, "minutes must be below 60");
  if (sec >= 60.0) fail(text, "seconds must be below 60");
  return Angle::degrees(sign * (d + m / 60.0 + sec / 3600.0));
}

std::string format_dms(Angle a, const DmsFormat& f) {
  const double deg = a.deg();
  if (std::isnan(deg)) return "nan";
  if (std::isinf(deg)) return deg > 0 ? "inf" : "-inf";
  const int dec = f.second_decimals < 0 ? 0 : (f.second_decimals > 9 ? 9 : f.second_decimals);
  const double scale = std::pow(10.0, dec);
  // Work in integer units of the last printed digit so rounding carries.
  const double total = std::round(std::fabs(deg) * 3600.0 * scale);
  const bool negative = deg < 0 && total > 0;
  const double per_deg = 3600.0 * scale;
  const double per_min = 60.0 * scale;
  const double d = std::floor(total / per_deg);
  const double rem = total - d * per_deg;
  const double m = std::floor(rem / per_min);
  const double s = (rem - m * per_min) / scale;
  const char* sign = negative ? "-" : (f.force_sign ? "+" : "");
  const int width = dec > 0 ? dec + 3 : 2;
  if (f.symbols)
    return fmt::format("{}{:.0f}\u00B0{:02.0f}'{:0{}.{}f}\"", sign, d, m, s, width, dec);
  return fmt::format("{}{:.0f} {:02.0f} {:0{}.{}f}", sign, d, m, s, width, dec);
}

std::string format_direction_dms(Angle a, const DmsFormat& f) {
  Angle n = a.normalized_positive();
  std::string out = format_dms(n, f);
  // Rounding may give 360°00'00.0"; print it as 0°.
  DmsFormat g = f;
  g.force_sign = false;
  if (out.rfind("360", 0) == 0) out = format_dms(Angle::degrees(0), g);
  return out;
}

}  // namespace meridian
