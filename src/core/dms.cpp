#include "meridian/core/dms.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
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

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

std::size_t count_digits(std::string_view s) {
  std::size_t n = 0;
  while (n < s.size() && std::isdigit(static_cast<unsigned char>(s[n]))) ++n;
  return n;
}

// Digits with an optional fraction ("12", "12.5", ".5"); nullopt for anything else.
std::optional<double> unsigned_decimal(std::string_view s) {
  const std::size_t whole = count_digits(s);
  std::size_t n = whole, frac = 0;
  if (n < s.size() && s[n] == '.') {
    frac = count_digits(s.substr(n + 1));
    n += 1 + frac;
  }
  if (n != s.size() || whole + frac == 0) return std::nullopt;
  double v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v, std::chars_format::fixed);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

// A leading '-' or '+', removed from `s`: -1 or +1.
double take_sign(std::string_view& s) {
  if (s.empty() || (s.front() != '-' && s.front() != '+')) return 1.0;
  const double sign = s.front() == '-' ? -1.0 : 1.0;
  s.remove_prefix(1);
  return sign;
}

// A plain decimal in `unit`, optionally followed by that unit's own marks.
Angle decimal_in_unit(std::string_view text, AngleUnit unit) {
  std::string_view s = trim(text);
  const double sign = take_sign(s);
  const bool gon = unit == AngleUnit::Gon;
  const std::string_view marks_deg[] = {"\xC2\xB0", "deg"};
  const std::string_view marks_gon[] = {"gon", "g"};
  for (std::string_view m : gon ? std::span<const std::string_view>(marks_gon)
                                : std::span<const std::string_view>(marks_deg)) {
    if (s.size() >= m.size() && s.substr(s.size() - m.size()) == m) {
      s = trim(s.substr(0, s.size() - m.size()));
      break;
    }
  }
  const auto v = unsigned_decimal(s);
  if (!v)
    throw ParseError(fmt::format(
        "cannot read angle \"{}\": angle_unit is {}, so write decimal {} such as \"{}\"", text,
        to_string(unit), gon ? "gon" : "degrees", gon ? "174.8333" : "157.3500"));
  return gon ? Angle::gon(sign * *v) : Angle::degrees(sign * *v);
}

[[noreturn]] void fail_ddd(std::string_view text, const std::string& why) {
  throw ParseError(
      fmt::format("cannot read angle \"{}\" as ddd.mmss (123.4530 = 123°45'30\"): {}", text, why));
}

[[noreturn]] void fail_time(std::string_view text, const std::string& why) {
  throw ParseError(fmt::format("cannot read time \"{}\": {}", text, why));
}

}  // namespace

AngleUnit angle_unit_from_string(std::string_view name) {
  for (AngleUnit u : {AngleUnit::Dms, AngleUnit::Degrees, AngleUnit::Gon, AngleUnit::DddMmss})
    if (to_string(u) == name) return u;
  throw ParseError(
      fmt::format("unknown angle unit \"{}\" (expected dms, deg, gon or ddd.mmss)", name));
}

std::string to_string(AngleUnit unit) {
  switch (unit) {
    case AngleUnit::Dms:
      return "dms";
    case AngleUnit::Degrees:
      return "deg";
    case AngleUnit::Gon:
      return "gon";
    case AngleUnit::DddMmss:
      return "ddd.mmss";
  }
  return "?";
}

Angle parse_angle(std::string_view text, AngleUnit unit) {
  switch (unit) {
    case AngleUnit::Dms:
      return parse_angle(text);
    case AngleUnit::Degrees:
    case AngleUnit::Gon:
      return decimal_in_unit(text, unit);
    case AngleUnit::DddMmss:
      return parse_ddd_mmss(text);
  }
  throw ParseError("unknown angle unit");
}

Angle parse_ddd_mmss(std::string_view text) {
  std::string_view s = trim(text);
  const double sign = take_sign(s);
  const std::size_t whole = count_digits(s);
  if (whole == 0) fail_ddd(text, "expected digits of degrees");
  std::string_view frac;
  if (whole < s.size()) {
    if (s[whole] != '.') fail_ddd(text, "only digits, one point and a leading sign are allowed");
    frac = s.substr(whole + 1);
    if (frac.empty() || count_digits(frac) != frac.size())
      fail_ddd(text, "only digits may follow the point");
  }
  if (frac.size() == 1 || frac.size() == 3)
    fail_ddd(text,
             fmt::format("{} digit{} after the point: write minutes and seconds with two digits "
                         "each (123.4030 for 123°40'30\", 123.0403 for 123°04'03\")",
                         frac.size(), frac.size() == 1 ? "" : "s"));
  double deg = 0;
  std::from_chars(s.data(), s.data() + whole, deg, std::chars_format::fixed);
  const double min = frac.empty() ? 0.0 : (frac[0] - '0') * 10.0 + (frac[1] - '0');
  double sec = 0;
  std::string sec_text = "0";
  if (frac.size() >= 4) {
    sec_text = std::string(frac.substr(2, 2));
    if (frac.size() > 4) sec_text += "." + std::string(frac.substr(4));
    std::from_chars(sec_text.data(), sec_text.data() + sec_text.size(), sec,
                    std::chars_format::fixed);
  }
  if (min >= 60.0)
    fail_ddd(text, fmt::format("minutes {:02.0f} must be below 60 (decimal degrees booked with the "
                               "wrong angle_unit?)",
                               min));
  if (sec >= 60.0)
    fail_ddd(text, fmt::format("seconds {} must be below 60 (decimal degrees booked with the wrong "
                               "angle_unit?)",
                               sec_text));
  if (!std::isfinite(deg)) fail_ddd(text, "not a finite number");
  return Angle::degrees(sign * (deg + min / 60.0 + sec / 3600.0));
}

std::string format_ddd_mmss(Angle a, int second_decimals) {
  const double deg = a.deg();
  if (std::isnan(deg)) return "nan";
  if (std::isinf(deg)) return deg > 0 ? "inf" : "-inf";
  const int dec = second_decimals < 0 ? 0 : (second_decimals > 6 ? 6 : second_decimals);
  std::int64_t scale = 1;
  for (int i = 0; i < dec; ++i) scale *= 10;
  // Integer units of the last printed digit, so rounding carries.
  const auto total =
      static_cast<std::int64_t>(std::llround(std::fabs(deg) * 3600.0 * static_cast<double>(scale)));
  const std::int64_t d = total / (3600 * scale);
  const std::int64_t m = (total / (60 * scale)) % 60;
  const std::int64_t s = total % (60 * scale);  // seconds in units of 10^-dec
  const char* sign = deg < 0 && total > 0 ? "-" : "";
  return fmt::format("{}{}.{:02}{:0{}}", sign, d, m, s, dec + 2);
}

double parse_stopwatch_s(std::string_view text) {
  const std::string_view s = trim(text);
  if (s.empty()) fail_time(text, "empty");
  if (s.find('-') != std::string_view::npos) fail_time(text, "a time cannot be negative");
  std::vector<std::string_view> parts;
  bool sexagesimal = true;
  if (s.find(':') != std::string_view::npos) {
    std::size_t b = 0;
    for (std::size_t e = s.find(':');; e = s.find(':', b)) {
      parts.push_back(s.substr(b, e == std::string_view::npos ? e : e - b));
      if (e == std::string_view::npos) break;
      b = e + 1;
    }
  } else {
    // m′ss.s″ or m'ss.s" (the seconds mark optional).
    std::size_t mark = s.find('\'');
    std::size_t mark_len = 1;
    if (const std::size_t p = s.find("\xE2\x80\xB2"); p < mark) mark = p, mark_len = 3;
    if (mark == std::string_view::npos) {
      sexagesimal = false;
      parts.push_back(s);
    } else {
      std::string_view sec = s.substr(mark + mark_len);
      for (std::string_view m : {"\"", "\xE2\x80\xB3", "''"})
        if (sec.size() >= m.size() && sec.substr(sec.size() - m.size()) == m) {
          sec.remove_suffix(m.size());
          break;
        }
      parts = {trim(s.substr(0, mark)), trim(sec)};
    }
  }
  const char* forms = "expected seconds (279.6) or a stopwatch reading m:ss.s or h:mm:ss.s";
  if (!sexagesimal) {
    const auto v = unsigned_decimal(parts[0]);
    if (!v) fail_time(text, forms);
    return *v;
  }
  if (parts.size() > 3) fail_time(text, "more than three parts (h:mm:ss.s)");
  double total = 0;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::string_view p = parts[i];
    const bool last = i + 1 == parts.size();
    const std::size_t digits = count_digits(p);
    if (p.empty() || digits == 0)
      fail_time(text, fmt::format("{} (part {} is empty)", forms, i + 1));
    if (!last && digits != p.size())
      fail_time(text, "only the seconds may have decimals: " + std::string(forms));
    const auto v = unsigned_decimal(p);
    if (!v) fail_time(text, forms);
    if (i > 0 && digits != 2)
      fail_time(text, fmt::format("write {} with two digits (e.g. 4:07.3)",
                                  last ? "seconds" : "minutes"));
    if (i > 0 && *v >= 60.0)
      fail_time(text, fmt::format("{} must be below 60", last ? "seconds" : "minutes"));
    total = total * 60.0 + *v;
  }
  return total;
}

Angle parse_angle(std::string_view text) {
  // Decimal degrees in exponent notation ("4.98e-19", as %.17g writes values below 1e-4):
  // the whole text one number with an exponent. No unit marker contains an 'e', so nothing
  // else reads this way.
  if (std::string_view t = trim(text); t.find_first_of("eE") != std::string_view::npos) {
    const double sign = take_sign(t);
    double v = 0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), v, std::chars_format::scientific);
    if (!t.empty() && t.front() != '-' && r.ec == std::errc() && r.ptr == t.data() + t.size() &&
        std::isfinite(v))
      return Angle::degrees(sign * v);
  }
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
