#include "meridian/io/nmea.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <system_error>
#include <string_view>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "input_limits.hpp"

namespace meridian::io::nmea {
namespace {

constexpr double kKnot_m_s = 1852.0 / 3600.0;
constexpr double kSecondsPerDay = 86400.0;
// More distinct talker+type keys than any real log has: beyond it duplicates are not tracked,
// so a hostile file cannot grow the memory.
constexpr std::size_t kMaxTrackedKeys = 1024;

// A field that cannot be decoded; the reason becomes the malformed line's reason.
struct NmeaDecodeError {
  std::string reason;
};

using Fields = std::vector<std::string_view>;

std::vector<std::string_view> nmea_split(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = s.find(',', start);
    out.push_back(s.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

std::string_view field_at(const Fields& f, std::size_t i) { return i < f.size() ? f[i] : std::string_view{}; }

std::optional<double> nmea_number(const Fields& f, std::size_t i) {
  const std::string_view s = field_at(f, i);
  if (s.empty()) return std::nullopt;
  double v = 0.0;
  const char* first = s.data() + (s.front() == '+' ? 1 : 0);
  const auto [ptr, ec] = std::from_chars(first, s.data() + s.size(), v);
  if (ec != std::errc{} || ptr != s.data() + s.size() || !std::isfinite(v))
    throw NmeaDecodeError{fmt::format("field {}: \"{}\" is not a number", i, s)};
  return v;
}

std::optional<int> nmea_integer(const Fields& f, std::size_t i) {
  const auto v = nmea_number(f, i);
  if (!v) return std::nullopt;
  if (*v != std::floor(*v) || std::fabs(*v) > 1e9)
    throw NmeaDecodeError{fmt::format("field {}: \"{}\" is not an integer", i, field_at(f, i))};
  return static_cast<int>(*v);
}

// ddmm.mmm (latitude) or dddmm.mmm (longitude) with its hemisphere letter.
std::optional<double> nmea_angle(const Fields& f, std::size_t i, char positive, char negative, double max_deg) {
  const auto v = nmea_number(f, i);
  const std::string_view h = field_at(f, i + 1);
  if (!v) return std::nullopt;
  if (h.size() != 1 || (h[0] != positive && h[0] != negative))
    throw NmeaDecodeError{fmt::format("field {}: hemisphere \"{}\" is not {} or {}", i + 1, h, positive, negative)};
  const double deg = std::floor(*v / 100.0);
  const double minutes = *v - 100.0 * deg;
  if (*v < 0.0 || minutes >= 60.0 || deg + minutes / 60.0 > max_deg)
    throw NmeaDecodeError{fmt::format("field {}: \"{}\" is not a ddmm.mmm angle", i, field_at(f, i))};
  const double rad = (deg + minutes / 60.0) * units::kDegree;
  return h[0] == positive ? rad : -rad;
}

// Degrees clockwise from north → [0, 2π).
std::optional<double> nmea_direction(const Fields& f, std::size_t i) {
  const auto v = nmea_number(f, i);
  if (!v) return std::nullopt;
  double r = std::fmod(*v * units::kDegree, units::kTwoPi);
  if (r < 0.0) r += units::kTwoPi;
  return r;
}

// hhmmss(.sss) → seconds since 00:00.
std::optional<double> nmea_time_of_day(const Fields& f, std::size_t i) {
  const std::string_view s = field_at(f, i);
  const auto v = nmea_number(f, i);
  if (!v) return std::nullopt;
  const double h = std::floor(*v / 10000.0), m = std::floor((*v - 10000.0 * h) / 100.0);
  const double sec = *v - 10000.0 * h - 100.0 * m;
  if (s.size() < 6 || *v < 0.0 || h >= 24.0 || m >= 60.0 || sec >= 61.0)
    throw NmeaDecodeError{fmt::format("field {}: \"{}\" is not an hhmmss time", i, s)};
  return 3600.0 * h + 60.0 * m + sec;
}

std::optional<bool> nmea_status(const Fields& f, std::size_t i) {
  const std::string_view s = field_at(f, i);
  if (s.empty()) return std::nullopt;
  if (s == "A") return true;
  if (s == "V") return false;
  throw NmeaDecodeError{fmt::format("field {}: status \"{}\" is not A or V", i, s)};
}

std::optional<double> knots(const Fields& f, std::size_t i) {
  const auto v = nmea_number(f, i);
  return v ? std::optional<double>(*v * kKnot_m_s) : std::nullopt;
}

void need_fields(const Fields& f, std::size_t n) {
  if (f.size() < n) throw NmeaDecodeError{fmt::format("{} fields, at least {} expected", f.size() - 1, n - 1)};
}

std::optional<std::int64_t> checked_date(int year, int month, int day) {
  if (month < 1 || month > 12 || day < 1 || day > 31 || year < 1900 || year > 2200) return std::nullopt;
  return days_from_civil(year, month, day);
}

Data decode(std::string_view type, const Fields& f) {
  if (type == "GGA") {
    need_fields(f, 10);
    return Gga{nmea_time_of_day(f, 1), nmea_angle(f, 2, 'N', 'S', 90.0), nmea_angle(f, 4, 'E', 'W', 180.0),
               nmea_integer(f, 6), nmea_integer(f, 7), nmea_number(f, 8), nmea_number(f, 9)};
  }
  if (type == "HDT") {
    need_fields(f, 2);
    return Hdt{nmea_direction(f, 1)};
  }
  if (type == "VTG") {
    if (f.size() == 5) return Vtg{nmea_direction(f, 1), knots(f, 3)};  // NMEA 1.x: no unit letters
    need_fields(f, 9);
    Vtg v{nmea_direction(f, 1), knots(f, 5)};
    if (!v.speed_m_s)
      if (const auto kmh = nmea_number(f, 7)) v.speed_m_s = *kmh / 3.6;
    return v;
  }
  if (type == "VBW") {
    need_fields(f, 7);
    return Vbw{knots(f, 1), knots(f, 2), nmea_status(f, 3), knots(f, 4), knots(f, 5), nmea_status(f, 6)};
  }
  if (type == "RMC") {
    need_fields(f, 10);
    Rmc r{nmea_time_of_day(f, 1), nmea_status(f, 2), nmea_angle(f, 3, 'N', 'S', 90.0),
          nmea_angle(f, 5, 'E', 'W', 180.0), knots(f, 7), nmea_direction(f, 8), std::nullopt};
    if (const std::string_view d = f[9]; !d.empty()) {
      const auto v = nmea_integer(f, 9);
      const int yy = *v % 100;
      r.date_days = checked_date(yy >= 80 ? 1900 + yy : 2000 + yy, (*v / 100) % 100, *v / 10000);
      if (d.size() != 6 || !r.date_days)
        throw NmeaDecodeError{fmt::format("field 9: \"{}\" is not a ddmmyy date", d)};
    }
    return r;
  }
  if (type == "ZDA") {
    need_fields(f, 5);
    Zda z{nmea_time_of_day(f, 1), std::nullopt};
    const auto day = nmea_integer(f, 2), month = nmea_integer(f, 3), year = nmea_integer(f, 4);
    if (day && month && year) {
      z.date_days = checked_date(*year, *month, *day);
      if (!z.date_days) throw NmeaDecodeError{"fields 2-4: not a day, month, year"};
    }
    return z;
  }
  if (type == "GLL") {
    need_fields(f, 5);
    return Gll{nmea_angle(f, 1, 'N', 'S', 90.0), nmea_angle(f, 3, 'E', 'W', 180.0), nmea_time_of_day(f, 5),
               nmea_status(f, 6)};
  }
  return std::monostate{};
}

// "YYYY-MM-DDThh:mm:ss[.f…][Z]" (a space for the T too) → seconds since 1970.
std::optional<double> logger_stamp(std::string_view s) {
  if (s.size() < 19) return std::nullopt;
  auto digits = [&](std::size_t pos, std::size_t n) -> std::optional<int> {
    int v = 0;
    for (std::size_t k = pos; k < pos + n; ++k) {
      if (s[k] < '0' || s[k] > '9') return std::nullopt;
      v = 10 * v + (s[k] - '0');
    }
    return v;
  };
  const auto y = digits(0, 4), mo = digits(5, 2), d = digits(8, 2), h = digits(11, 2), mi = digits(14, 2),
             se = digits(17, 2);
  if (!y || !mo || !d || !h || !mi || !se || s[4] != '-' || s[7] != '-' || (s[10] != 'T' && s[10] != ' ') ||
      s[13] != ':' || s[16] != ':' || *h > 23 || *mi > 59 || *se > 60)
    return std::nullopt;
  const auto days = checked_date(*y, *mo, *d);
  if (!days) return std::nullopt;
  double frac = 0.0;
  std::size_t k = 19;
  if (k < s.size() && s[k] == '.') {
    double scale = 0.1;
    for (++k; k < s.size() && s[k] >= '0' && s[k] <= '9'; ++k, scale /= 10.0) frac += (s[k] - '0') * scale;
  }
  if (k < s.size() && s[k] == 'Z') ++k;
  if (k != s.size()) return std::nullopt;
  return static_cast<double>(*days) * kSecondsPerDay + 3600.0 * *h + 60.0 * *mi + *se + frac;
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

// Reads line `n` into `out`, storing at most kMaxLineBytes + 1 bytes; false at end of input.
// A line beyond detail::kMaxTextLineBytes (1 MiB) is no NMEA log (a file without line ends,
// /dev/zero on stdin): ParseError, instead of reading it to the end.
bool next_nmea_line(std::streambuf& sb, std::string& out, bool& overlong, const std::string& source, int n) {
  out.clear();
  overlong = false;
  bool any = false;
  std::size_t length = 0;
  for (;;) {
    const int c = sb.sbumpc();
    if (c == std::char_traits<char>::eof()) return any;
    any = true;
    if (c == '\n') return true;
    if (out.size() <= kMaxLineBytes)
      out.push_back(static_cast<char>(c));
    else
      overlong = true;
    if (++length > detail::kMaxTextLineBytes) throw detail::line_too_long(source, n);
  }
}

class Inspector {
 public:
  Inspector(const std::string& source, const Options& options, const std::function<void(const Sentence&)>& cb)
      : options_(options), cb_(cb) {
    s_.file = source;
    s_.accept_missing_checksum = options.accept_missing_checksum;
  }

  void line(int n, std::string& text, bool overlong) {
    ++s_.lines;
    // A UTF-8 byte-order mark before the first line (editors on Windows write one).
    if (n == 1 && text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);
    while (!text.empty() && (text.back() == '\r' || text.back() == ' ' || text.back() == '\t')) text.pop_back();
    if (overlong || text.size() > kMaxLineBytes) return malformed(n, fmt::format("longer than {} bytes", kMaxLineBytes));
    const std::size_t first = text.find_first_not_of(" \t");
    if (first == std::string::npos) return void(++s_.blank);
    if (text[first] == '#') return void(++s_.comments);
    const std::size_t dollar = text.find('$');
    if (dollar == std::string::npos) return malformed(n, "no '$'");
    for (char c : text)
      if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || static_cast<unsigned char>(c) > 0x7e)
        return malformed(n, "a byte that is not printable ASCII");
    if (dollar + 1 == text.size() || text[dollar + 1] == ',' || text[dollar + 1] == '*')
      return malformed(n, "no talker and type after '$'");
    Sentence st;
    st.line = n;
    if (dollar > first) {
      ++s_.logger_prefixed;
      std::string_view prefix(text.data() + first, dollar - first);
      while (!prefix.empty() && (prefix.back() == ' ' || prefix.back() == '\t' || prefix.back() == ','))
        prefix.remove_suffix(1);
      st.logger_time_s = logger_stamp(prefix);
      // The logger's clock spans the file whatever becomes of the sentence after its stamp.
      widen(first_logger_, last_logger_, st.logger_time_s);
    }
    const std::string_view body(text.data() + dollar, text.size() - dollar);
    if (body.find('$', 1) != std::string_view::npos) return malformed(n, "a second '$' (truncated sentence)");
    const std::size_t star = body.find('*');
    std::string_view content = body.substr(1);
    if (star != std::string_view::npos) {
      const std::string_view sum = body.substr(star + 1);
      if (sum.size() != 2 || hex_digit(sum[0]) < 0 || hex_digit(sum[1]) < 0)
        return malformed(n, fmt::format("checksum \"{}\" is not two hex digits", sum));
      content = body.substr(1, star - 1);
      unsigned x = 0;
      for (char c : content) x ^= static_cast<unsigned char>(c);
      if (x != static_cast<unsigned>(16 * hex_digit(sum[0]) + hex_digit(sum[1]))) {
        ++s_.bad_checksum;
        if (s_.bad_checksum_lines.size() < kMaxLinesListed) s_.bad_checksum_lines.push_back(n);
        return;
      }
    } else if (!options_.accept_missing_checksum) {
      count_no_checksum(n, content.substr(0, content.find(',')));  // rejected here
      return;
    } else {
      st.has_checksum = false;  // counted once it is accepted: a malformed one is only malformed
    }
    decode_sentence(n, text, st, content);
  }

  // A framed sentence whose checksum passed (or is absent and accepted): its address, fields,
  // duplicates, date and time; delivered to the callback unless malformed or a duplicate.
  void decode_sentence(int n, const std::string& text, Sentence& st, std::string_view content) {
    const Fields f = nmea_split(content);
    const std::string_view address = f[0];
    if (!address.empty() && address[0] == 'P') return void(++s_.proprietary);
    if (address.size() != 5) return malformed(n, fmt::format("address \"{}\" is not talker + type", address));
    for (char c : address)
      if (!((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9')))
        return malformed(n, fmt::format("address \"{}\" is not talker + type", address));
    st.talker = address.substr(0, 2);
    st.type = address.substr(2);
    try {
      st.data = decode(st.type, f);
    } catch (const NmeaDecodeError& e) {
      return malformed(n, fmt::format("{}: {}", address, e.reason));
    }
    const std::string key(address);
    if (!st.has_checksum) count_no_checksum(n, address);
    ++s_.sentences[key];
    if (std::holds_alternative<std::monostate>(st.data)) ++s_.unknown;
    // Only a repeated time is a duplicate: an untimed sentence repeats whenever the value is
    // steady (a constant heading), a timed one repeats an epoch that already exists.
    bool duplicate = false;
    if (time_of_day(st.data)) {
      if (auto it = last_.find(key); it != last_.end()) {
        duplicate = it->second == text;
        it->second = text;
      } else if (last_.size() < kMaxTrackedKeys) {
        last_.emplace(key, text);
      }
    }
    if (duplicate) {
      ++s_.duplicates, ++s_.duplicates_by_type[key];
      return;
    }
    date_and_time(st);
    widen(first_time_, last_time_, st.time_s);
    if (cb_) cb_(st);
  }

  Summary finish() {
    if (first_time_) {
      s_.first_time_s = first_time_, s_.last_time_s = last_time_, s_.time_source = "sentences";
    } else if (first_logger_) {
      s_.first_time_s = first_logger_, s_.last_time_s = last_logger_, s_.time_source = "logger";
    }
    return std::move(s_);
  }

 private:
  // Receivers do not always send in time order (a GGA of 23:59:59.9 after the ZDA of 00:00).
  static void widen(std::optional<double>& lo, std::optional<double>& hi, const std::optional<double>& t) {
    if (!t) return;
    if (!lo || *t < *lo) lo = t;
    if (!hi || *t > *hi) hi = t;
  }

  void count_no_checksum(int n, std::string_view address) {
    ++s_.no_checksum;
    if (s_.no_checksum_lines.size() < kMaxLinesListed) s_.no_checksum_lines.push_back(n);
    bool ok = address.size() == 5;
    for (char c : address) ok = ok && ((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'));
    if (!ok) return;
    const std::string key(address);
    if (auto it = s_.no_checksum_by_type.find(key); it != s_.no_checksum_by_type.end())
      ++it->second;
    else if (s_.no_checksum_by_type.size() < kMaxTrackedKeys)
      s_.no_checksum_by_type.emplace(key, 1);
  }

  void malformed(int n, std::string reason) {
    ++s_.malformed;
    if (s_.malformed_lines.size() < kMaxLinesListed) s_.malformed_lines.emplace_back(n, std::move(reason));
  }

  // Dates the sentence: its own date (RMC, ZDA) or the latest one, the time of day put on the
  // day nearest to the last dated instant (midnight crossings).
  static std::optional<double> time_of_day(const Data& d) {
    if (const auto* g = std::get_if<Gga>(&d)) return g->time_of_day_s;
    if (const auto* g = std::get_if<Gll>(&d)) return g->time_of_day_s;
    if (const auto* r = std::get_if<Rmc>(&d)) return r->time_of_day_s;
    if (const auto* z = std::get_if<Zda>(&d)) return z->time_of_day_s;
    return std::nullopt;
  }

  void date_and_time(Sentence& st) {
    const std::optional<double> tod = time_of_day(st.data);
    std::optional<std::int64_t> date;
    if (const auto* r = std::get_if<Rmc>(&st.data)) date = r->date_days;
    if (const auto* z = std::get_if<Zda>(&st.data)) date = z->date_days;
    if (date) {
      if (!s_.first_date_days) s_.first_date_days = date;
      const double day_s = static_cast<double>(*date) * kSecondsPerDay;
      const double stamp = st.logger_time_s.value_or(std::nan(""));
      const bool rolled = st.logger_time_s ? stamp - day_s >= (kGpsRolloverDays - 1) * kSecondsPerDay
                                           : *date < days_from_civil(2000, 1, 1);
      if (rolled && !s_.gps_week_rollover_suspected) s_.gps_week_rollover_suspected = true, s_.rollover_line = st.line;
      if (tod) st.time_s = ref_s_ = day_s + *tod;
      return;
    }
    if (!tod || !ref_s_) return;
    double t = std::floor(*ref_s_ / kSecondsPerDay) * kSecondsPerDay + *tod;
    if (t - *ref_s_ > kSecondsPerDay / 2) t -= kSecondsPerDay;
    if (*ref_s_ - t > kSecondsPerDay / 2) t += kSecondsPerDay;
    st.time_s = ref_s_ = t;
  }

  const Options& options_;
  const std::function<void(const Sentence&)>& cb_;
  Summary s_;
  std::map<std::string, std::string> last_;  // the previous line of each talker+type
  std::optional<double> ref_s_;
  std::optional<double> first_time_, last_time_, first_logger_, last_logger_;
};

}  // namespace

Summary read(std::istream& in, const std::string& source, const Options& options,
             const std::function<void(const Sentence&)>& on_sentence) {
  Inspector inspector(source, options, on_sentence);
  std::string text;
  bool overlong = false;
  int n = 0;
  std::streambuf* sb = in.rdbuf();
  if (!sb) throw IoError("cannot read", {source, std::nullopt, ""});
  while (next_nmea_line(*sb, text, overlong, source, n + 1)) inspector.line(++n, text, overlong);
  if (in.bad()) throw IoError("read error", {source, n, ""});
  return inspector.finish();
}

Summary read_file(const std::string& path, const Options& options,
                  const std::function<void(const Sentence&)>& on_sentence) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw IoError("is a directory, not a file", {path, std::nullopt, ""});
  detail::check_readable_path(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot open the file", {path, std::nullopt, ""});
  return read(in, path, options, on_sentence);
}

std::vector<Summary> inspect_files(const std::vector<std::string>& paths, bool accept_missing_checksum) {
  Options o;
  o.accept_missing_checksum = accept_missing_checksum;
  std::vector<Summary> summaries;
  for (const std::string& p : paths) summaries.push_back(read_file(p, o));
  return summaries;
}

}  // namespace meridian::io::nmea
