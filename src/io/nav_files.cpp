#include "meridian/io/nav_files.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/io/nmea.hpp"
#include "meridian/io/record_reader.hpp"
#include "input_limits.hpp"

namespace meridian::io {
namespace {
// Unity builds put this file beside the other io_nav sources: every helper lives in navf.
namespace navf {

constexpr double kDeg = units::kDegree;

std::string ascii_lower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

void require_header(RecordReader& rr, const char* what, const char* columns) {
  if (rr.header().empty())
    throw InputError(fmt::format("a {} file needs a header line naming its columns ({})", what, columns),
                     ErrorContext{rr.source(), std::nullopt, {}});
}

/// Position columns: x_m, y_m or lat_deg, lon_deg (exactly one pair).
struct PositionColumns {
  bool geographic = false;
  std::size_t a = 0, b = 0;
};

PositionColumns position_columns(RecordReader& rr, const char* what) {
  const auto x = rr.find_column("x_m"), y = rr.find_column("y_m");
  const auto lat = rr.find_column("lat_deg"), lon = rr.find_column("lon_deg");
  const bool plane = x || y, geo = lat || lon;
  const ErrorContext header{rr.source(), rr.header_line(), {}};
  if (plane && geo)
    throw InputError(fmt::format("a {} file gives x_m, y_m or lat_deg, lon_deg, not both", what), header);
  if (!plane && !geo)
    throw InputError(fmt::format("a {} file needs the columns x_m, y_m (plane, x north) or lat_deg, lon_deg",
                                 what),
                     header);
  PositionColumns c;
  c.geographic = geo;
  c.a = rr.require_column(geo ? "lat_deg" : "x_m");
  c.b = rr.require_column(geo ? "lon_deg" : "y_m");
  return c;
}

NavPosition read_position(const Record& r, const PositionColumns& c) {
  NavPosition p;
  p.geographic = c.geographic;
  if (c.geographic) {
    p.lat_rad = r.angle(c.a).rad();
    if (!(std::abs(p.lat_rad) <= units::kPi / 2))
      throw InputError(fmt::format("latitude {}° is beyond ±90°", p.lat_rad / kDeg), r.context(c.a));
    p.lon_rad = r.angle(c.b).rad();
  } else {
    p.x_north_m = r.number(c.a);
    p.y_east_m = r.number(c.b);
  }
  return p;
}

// A true position is compared with every estimate: a value no ship has (1e308 m made every RMS
// "n/a") is refused at its line. Plane coordinates within 1e8 m (2.5 times the Earth's
// circumference) and longitudes within ±360°: Meridian's bounds.
constexpr double kMaxTruthPlane_m = 1e8;
void check_truth_position(const Record& r, const PositionColumns& c, const NavPosition& p) {
  if (c.geographic) {
    if (!(std::abs(p.lon_rad) <= 2 * units::kPi))
      throw InputError(fmt::format("true longitude {:g}° is beyond ±360°", p.lon_rad / kDeg), r.context(c.b));
    return;
  }
  if (!(std::abs(p.x_north_m) <= kMaxTruthPlane_m))
    throw InputError(fmt::format("true coordinate {:g} m is beyond ±{:g} m: not a position", p.x_north_m, kMaxTruthPlane_m),
                     r.context(c.a));
  if (!(std::abs(p.y_east_m) <= kMaxTruthPlane_m))
    throw InputError(fmt::format("true coordinate {:g} m is beyond ±{:g} m: not a position", p.y_east_m, kMaxTruthPlane_m),
                     r.context(c.b));
}

double positive(const Record& r, std::size_t col, const char* what) {
  const double v = r.number(col);
  if (!(v > 0.0)) throw InputError(fmt::format("{} must be > 0, not {}", what, v), r.context(col));
  return v;
}

std::ifstream open_or_throw(const std::string& path, const char* what) {
  detail::check_readable_path(path);
  std::ifstream f(path, std::ios::binary);
  std::error_code ec;
  if (!f || std::filesystem::is_directory(path, ec))
    throw IoError(fmt::format("cannot open {} file {}", what, path), ErrorContext{path, {}, {}});
  return f;
}

// Every record, after checking that it has no field beyond the header's columns (a value
// there would be silently ignored; empty trailing fields, as spreadsheets write, are fine).
template <class Fn>
void for_each_record(RecordReader& rr, Fn&& fn) {
  RecordChunk chunk;
  const std::size_t columns = rr.header().size();
  while (rr.next(chunk, 16384))
    for (std::size_t k = 0; k < chunk.size(); ++k) {
      const Record r = chunk[k];
      for (std::size_t c = columns; c < r.size(); ++c)
        if (!r.field(c).empty())
          throw InputError(fmt::format("{} fields, but the header (line {}) names {} columns: \"{}\" in field {} "
                                       "has no column",
                                       r.size(), rr.header_line(), columns, r.field(c), c + 1),
                           r.context());
      fn(r);
    }
}

std::string comment_line(const std::string& settings) {
  if (settings.empty()) return {};
  std::string one = settings;
  for (char& ch : one)
    if (ch == '\n' || ch == '\r') ch = ' ';
  return "# " + one + "\n";
}

const char* lop_type_name(NavLopKind k) {
  switch (k) {
    case NavLopKind::Range: return "range";
    case NavLopKind::RangeDifference: return "range_difference";
    case NavLopKind::TimeDifference: return "time_difference";
  }
  return "range";
}

}  // namespace navf
}  // namespace

// ---- readers ---------------------------------------------------------------------------------

NavDrFile read_nav_dr(std::istream& in, const std::string& source) {
  RecordReader rr(in, source);
  navf::require_header(rr, "DR", "time_s, speed_m_s, heading_deg or time_s, v_north_m_s, v_east_m_s");
  NavDrFile out;
  out.source = source;
  const std::size_t t = rr.require_column("time_s");
  const auto speed = rr.find_column("speed_m_s"), vn = rr.find_column("v_north_m_s");
  if (speed && vn)
    throw InputError("a DR file gives speed_m_s, heading_deg or v_north_m_s, v_east_m_s, not both",
                     ErrorContext{source, rr.header_line(), {}});
  if (!speed && !vn)
    throw InputError("a DR file needs the columns speed_m_s, heading_deg or v_north_m_s, v_east_m_s",
                     ErrorContext{source, rr.header_line(), {}});
  out.speed_heading = speed.has_value();
  const std::size_t a = speed ? *speed : *vn;
  const std::size_t b = rr.require_column(speed ? "heading_deg" : "v_east_m_s");
  navf::for_each_record(rr, [&](const Record& r) {
    NavDrFile::Record d;
    d.time_s = r.number(t);
    d.a = r.number(a);
    if (out.speed_heading) {
      if (d.a < 0.0) throw InputError(fmt::format("speed {} m/s is negative", d.a), r.context(a));
      d.b = r.angle(b).rad();
    } else {
      d.b = r.number(b);
    }
    if (!out.records.empty() && !(d.time_s > out.records.back().time_s))
      throw InputError(fmt::format("time {} s is not after {} s of line {}: DR times must increase strictly",
                                   d.time_s, out.records.back().time_s, out.lines.back()),
                       r.context(t));
    out.records.push_back(d);
    out.lines.push_back(r.line());
  });
  return out;
}

NavStationsFile read_nav_stations(std::istream& in, const std::string& source) {
  RecordReader rr(in, source);
  navf::require_header(rr, "stations", "name, x_m, y_m or name, lat_deg, lon_deg");
  NavStationsFile out;
  out.source = source;
  const std::size_t name = rr.require_column("name");
  const navf::PositionColumns pc = navf::position_columns(rr, "stations");
  std::map<std::string, int> seen;
  navf::for_each_record(rr, [&](const Record& r) {
    const std::string n(r.field(name));
    if (n.empty()) throw InputError("a station needs a name", r.context(name));
    if (auto [it, fresh] = seen.emplace(n, r.line()); !fresh)
      throw InputError(fmt::format("station \"{}\" is already defined on line {}", n, it->second),
                       r.context(name));
    out.names.push_back(n);
    out.positions.push_back(navf::read_position(r, pc));
    out.lines.push_back(r.line());
  });
  return out;
}

NavLopsFile read_nav_lops(std::istream& in, const std::string& source) {
  RecordReader rr(in, source);
  navf::require_header(rr, "LOP", "time_s, type, station, station2, value, sigma_m[, chain]");
  NavLopsFile out;
  out.source = source;
  const std::size_t t = rr.require_column("time_s");
  const std::size_t type = rr.require_column("type");
  const std::size_t st = rr.require_column("station");
  const auto st2 = rr.find_column("station2");
  const std::size_t value = rr.require_column("value");
  const std::size_t sigma = rr.require_column("sigma_m");
  const auto chain = rr.find_column("chain");
  using Key = std::tuple<double, int, std::string, std::string, double, double, std::string>;
  std::map<Key, int> seen;
  navf::for_each_record(rr, [&](const Record& r) {
    NavLopsFile::Record l;
    l.time_s = r.number(t);
    const std::string ty = navf::ascii_lower(r.field(type));
    if (ty == "range")
      l.kind = NavLopKind::Range;
    else if (ty == "range_difference")
      l.kind = NavLopKind::RangeDifference;
    else if (ty == "time_difference")
      l.kind = NavLopKind::TimeDifference;
    else
      throw InputError(fmt::format("\"{}\" is not a LOP type (range, range_difference, time_difference)",
                                   r.field(type)),
                       r.context(type));
    l.station = std::string(r.field(st));
    if (l.station.empty()) throw InputError("a LOP needs a station", r.context(st));
    if (st2) l.station2 = std::string(r.field(*st2));
    if (l.kind == NavLopKind::Range && !l.station2.empty())
      throw InputError("a range has one station: leave station2 empty", r.context(*st2));
    if (l.kind != NavLopKind::Range) {
      if (l.station2.empty())
        throw InputError(fmt::format("a {} needs station2", navf::lop_type_name(l.kind)),
                         st2 ? r.context(*st2) : ErrorContext{source, r.line(), "station2"});
      if (l.station2 == l.station)
        throw InputError("station and station2 are the same station", r.context(*st2));
    }
    l.value = r.number(value);
    l.sigma_m = navf::positive(r, sigma, "sigma_m");
    if (chain) l.chain = std::string(r.field(*chain));
    const Key key{l.time_s, static_cast<int>(l.kind), l.station, l.station2, l.value, l.sigma_m, l.chain};
    if (auto [it, fresh] = seen.emplace(key, r.line()); !fresh)
      throw InputError(fmt::format("the same LOP as line {} (every value equal): remove one of lines {} and {}",
                                   it->second, it->second, r.line()),
                       r.context());
    out.records.push_back(l);
    out.lines.push_back(r.line());
  });
  return out;
}

NavFixesFile read_nav_fixes(std::istream& in, const std::string& source) {
  RecordReader rr(in, source);
  navf::require_header(rr, "fix", "time_s, x_m, y_m, sigma_m or time_s, lat_deg, lon_deg, sigma_m");
  NavFixesFile out;
  out.source = source;
  const std::size_t t = rr.require_column("time_s");
  const navf::PositionColumns pc = navf::position_columns(rr, "fix");
  const auto s = rr.find_column("sigma_m");
  const auto sx = rr.find_column("sigma_x_m"), sy = rr.find_column("sigma_y_m");
  const ErrorContext header{source, rr.header_line(), {}};
  if (s && (sx || sy)) throw InputError("a fix file gives sigma_m or sigma_x_m, sigma_y_m, not both", header);
  if (!s && !(sx && sy))
    throw InputError("a fix file needs the column sigma_m or both sigma_x_m and sigma_y_m", header);
  using Key = std::tuple<double, double, double, double, double>;
  std::map<Key, int> seen;
  navf::for_each_record(rr, [&](const Record& r) {
    NavFixesFile::Record f;
    f.time_s = r.number(t);
    f.position = navf::read_position(r, pc);
    if (s) {
      f.sigma_north_m = f.sigma_east_m = navf::positive(r, *s, "sigma_m");
    } else {
      f.sigma_north_m = navf::positive(r, *sx, "sigma_x_m");
      f.sigma_east_m = navf::positive(r, *sy, "sigma_y_m");
    }
    const Key key{f.time_s, pc.geographic ? f.position.lat_rad : f.position.x_north_m,
                  pc.geographic ? f.position.lon_rad : f.position.y_east_m, f.sigma_north_m, f.sigma_east_m};
    if (auto [it, fresh] = seen.emplace(key, r.line()); !fresh)
      throw InputError(fmt::format("the same fix as line {} (every value equal): remove one of lines {} and {}",
                                   it->second, it->second, r.line()),
                       r.context());
    out.records.push_back(f);
    out.lines.push_back(r.line());
  });
  return out;
}

NavTruthFile read_nav_truth(std::istream& in, const std::string& source) {
  RecordReader rr(in, source);
  navf::require_header(rr, "truth", "time_s, x_m, y_m or time_s, lat_deg, lon_deg");
  NavTruthFile out;
  out.source = source;
  const std::size_t t = rr.require_column("time_s");
  const navf::PositionColumns pc = navf::position_columns(rr, "truth");
  std::map<double, int> seen;
  navf::for_each_record(rr, [&](const Record& r) {
    NavTruthFile::Record p;
    p.time_s = r.number(t);
    if (auto [it, fresh] = seen.emplace(p.time_s, r.line()); !fresh)
      throw InputError(fmt::format("time {} s is already on line {}: one true position per time", p.time_s,
                                   it->second),
                       r.context(t));
    p.position = navf::read_position(r, pc);
    navf::check_truth_position(r, pc, p.position);
    out.records.push_back(p);
    out.lines.push_back(r.line());
  });
  return out;
}

NavDrFile read_nav_dr_file(const std::string& path) {
  auto f = navf::open_or_throw(path, "DR");
  return read_nav_dr(f, path);
}
NavStationsFile read_nav_stations_file(const std::string& path) {
  auto f = navf::open_or_throw(path, "stations");
  return read_nav_stations(f, path);
}
NavLopsFile read_nav_lops_file(const std::string& path) {
  auto f = navf::open_or_throw(path, "LOP");
  return read_nav_lops(f, path);
}
NavFixesFile read_nav_fixes_file(const std::string& path) {
  auto f = navf::open_or_throw(path, "fix");
  return read_nav_fixes(f, path);
}
NavTruthFile read_nav_truth_file(const std::string& path) {
  auto f = navf::open_or_throw(path, "truth");
  return read_nav_truth(f, path);
}

// ---- writers ---------------------------------------------------------------------------------

std::string nav_dr_csv(const std::vector<nav::DrSample>& dr, const std::string& settings) {
  std::string out = "# meridian nav DR: speed over ground (m/s), heading clockwise from x = north (deg)\n";
  out += navf::comment_line(settings);
  out += "time_s,speed_m_s,heading_deg\n";
  for (const nav::DrSample& d : dr) {
    double h = std::atan2(d.v_east_m_s, d.v_north_m_s) / navf::kDeg;
    if (h < 0.0) h += 360.0;
    out += fmt::format("{:.17g},{:.17g},{:.17g}\n", d.time_s, std::hypot(d.v_north_m_s, d.v_east_m_s), h);
  }
  return out;
}

std::string nav_stations_csv(const std::vector<nav::Station>& stations, const std::string& settings) {
  std::string out = "# meridian nav stations: plane x = north, y = east (m)\n";
  out += navf::comment_line(settings);
  out += "name,x_m,y_m\n";
  for (const nav::Station& s : stations)
    out += fmt::format("{},{:.17g},{:.17g}\n", s.name, s.x_north_m, s.y_east_m);
  return out;
}

std::string nav_lops_csv(const nav::Input& input, const std::string& settings) {
  std::string out = "# meridian nav lines of position (m)\n";
  out += navf::comment_line(settings);
  out += "time_s,type,station,station2,value,sigma_m,chain\n";
  for (const nav::Lop& l : input.lops) {
    const bool diff = l.type == nav::LopType::RangeDifference;
    const auto name = [&](std::size_t i) {
      return i < input.stations.size() ? input.stations[i].name : std::string();
    };
    out += fmt::format("{:.17g},{},{},{},{:.17g},{:.17g},{}\n", l.time_s, diff ? "range_difference" : "range",
                       name(l.station), diff ? name(l.station2) : std::string(), l.value_m, l.sigma_m,
                       l.chain < input.chains.size() ? input.chains[l.chain].name : std::string());
  }
  return out;
}

std::string nav_fixes_csv(const std::vector<nav::Fix>& fixes, const std::string& settings) {
  std::string out = "# meridian nav satellite fixes: plane x = north, y = east (m)\n";
  out += navf::comment_line(settings);
  out += "time_s,x_m,y_m,sigma_x_m,sigma_y_m\n";
  for (const nav::Fix& f : fixes)
    out += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", f.time_s, f.x_north_m, f.y_east_m,
                       std::sqrt(f.covariance(0, 0)), std::sqrt(f.covariance(1, 1)));
  return out;
}

std::string nav_truth_csv(const std::vector<nav::TruthPoint>& truth, const std::string& settings) {
  std::string out = "# meridian nav true positions: plane x = north, y = east (m)\n";
  out += navf::comment_line(settings);
  out += "time_s,x_m,y_m\n";
  for (const nav::TruthPoint& p : truth)
    out += fmt::format("{:.17g},{:.17g},{:.17g}\n", p.time_s, p.x_north_m, p.y_east_m);
  return out;
}

}  // namespace meridian::io
