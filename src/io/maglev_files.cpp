#include "meridian/io/maglev_files.hpp"

#include <cmath>
#include <fstream>
#include <iostream>
#include <optional>

#include <fmt/format.h>

#include "meridian/core/dms.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/io/document.hpp"
#include "meridian/io/record_reader.hpp"
#include "input_limits.hpp"

namespace meridian::io {
namespace {

// Meridian's bound on a sample's current: 1000 A, far beyond any maglev gyro (a fraction of
// an ampere) so that values 1000x too large (mA under an [A] header) still reach the reduction's
// own unit-slip message.
constexpr double kMaxCurrent_A = 1000.0;

struct Columns {
  std::size_t time = 0, current = 1;
  std::optional<std::size_t> position;
  double time_scale = 1.0;     // header unit → s
  double current_scale = 1.0;  // header unit → A
};

// The factor that turns a value in the header's unit into SI (s or A); the unit of a column
// the header names is never ignored: an unknown one is an input error at the header line.
double unit_scale(RecordReader& rr, std::size_t column, const char* field, bool current) {
  const auto& header = rr.header();
  if (column >= header.size()) return 1.0;
  const std::string& u = header[column].unit;
  if (current) {
    if (u.empty() || u == "A") return 1.0;
    if (u == "mA") return 1e-3;
    if (u == "uA" || u == "µA" || u == "μA") return 1e-6;
  } else {
    if (u.empty() || u == "s") return 1.0;
    if (u == "ms") return 1e-3;
    if (u == "min") return 60.0;
  }
  throw InputError(fmt::format("column `{}`: unit [{}] is not understood here (use {})",
                               header[column].name, u, current ? "A, mA or uA" : "s, ms or min"),
                   {rr.source(), rr.header_line(), field});
}

// How the calibration table's azimuth column is written: its header unit ([deg], [dms],
// [gon], [rad], [mrad]; none: DMS or decimal degrees as before). An unknown unit is an input
// error at the header line naming the column.
enum class AzimuthUnit { Dms, Degrees, Gon, Radians, Milliradians };

AzimuthUnit azimuth_unit(RecordReader& rr, std::size_t column) {
  const auto& header = rr.header();
  if (column >= header.size()) return AzimuthUnit::Dms;
  const std::string& u = header[column].unit;
  if (u.empty() || u == "dms" || u == "DMS") return AzimuthUnit::Dms;
  if (u == "deg" || u == "°") return AzimuthUnit::Degrees;
  if (u == "gon" || u == "grad") return AzimuthUnit::Gon;
  if (u == "rad") return AzimuthUnit::Radians;
  if (u == "mrad") return AzimuthUnit::Milliradians;
  throw InputError(
      fmt::format("column `{}`: unit [{}] is not understood (use deg, dms, gon, rad or mrad)",
                  header[column].name, u),
      {rr.source(), rr.header_line(), "azimuth"});
}

double read_azimuth(const Record& r, std::size_t column, AzimuthUnit unit) {
  switch (unit) {
    case AzimuthUnit::Dms:
      return r.angle(column, {"azimuth"}).rad();
    case AzimuthUnit::Degrees:
      return r.parse(column, [](std::string_view t) { return parse_angle(t, AngleUnit::Degrees); },
                     {"azimuth"})
          .rad();
    case AzimuthUnit::Gon:
      return r.parse(column, [](std::string_view t) { return parse_angle(t, AngleUnit::Gon); },
                     {"azimuth"})
          .rad();
    case AzimuthUnit::Radians:
      return r.number(column, {"azimuth", "azimuth"});
    case AzimuthUnit::Milliradians:
      return r.number(column, {"azimuth", "azimuth"}) * 1e-3;
  }
  return 0.0;
}

Columns series_columns(RecordReader& rr) {
  Columns c;
  if (!rr.header().empty()) {
    const auto t = rr.find_column("time");
    const auto i = rr.find_column("current");
    if (t && i) {
      c.time = *t;
      c.current = *i;
    }
    c.position = rr.find_column("position");
    c.time_scale = unit_scale(rr, c.time, "time", false);
    c.current_scale = unit_scale(rr, c.current, "current", true);
  }
  return c;
}

void read_into(RecordReader& rr, const Columns& c, int want, MaglevSeriesFile* one,
               MaglevSeriesFile* two) {
  RecordChunk chunk;
  const std::size_t need = std::max({c.time, c.current, c.position.value_or(0)}) + 1;
  const std::size_t allowed = std::max(need, rr.header().size());
  while (rr.next(chunk, 65536)) {
    for (std::size_t k = 0; k < chunk.size(); ++k) {
      const Record r = chunk[k];
      if (r.size() < need)
        throw InputError(fmt::format("expected {} columns (time, current{}), got {}", need,
                                     c.position ? ", position" : "", r.size()),
                         r.context());
      // A value beyond the columns the header names (or beyond time, current without a header)
      // is a stray value, not something to drop silently; empty trailing fields are allowed.
      for (std::size_t col = allowed; col < r.size(); ++col)
        if (!r.field(col).empty())
          throw InputError(
              fmt::format("unexpected value \"{}\" in column {}: the {} names {} columns", r.field(col),
                          col + 1, rr.header().empty() ? "format (time, current)" : "header",
                          allowed),
              r.context());
      int pos = want == 0 ? 1 : want;
      if (c.position) {
        const double p = r.number(*c.position, {"position", "position"});
        if (p != 1.0 && p != 2.0)
          throw InputError(fmt::format("position {} is neither 1 nor 2", p),
                           r.context(*c.position, {"position"}));
        pos = static_cast<int>(p);
      }
      MaglevSeriesFile* f = nullptr;
      if (two) {
        f = pos == 1 ? one : two;
      } else {
        if (want != 0 && pos != want)
          throw InputError(
              fmt::format("a sample of position {} in a file of position {}", pos, want),
              r.context(*c.position, {"position"}));
        f = one;
      }
      const double t = r.number(c.time, {"time", "time"}) * c.time_scale;
      const double i = r.number(c.current, {"current", "current"}) * c.current_scale;
      // A maglev gyro's current is well under an ampere; beyond kMaxCurrent_A it is no sample
      // (4e9 A ended in a numerical failure that named neither file nor line).
      if (!(std::abs(i) <= kMaxCurrent_A))
        throw InputError(fmt::format("current {:g} A is beyond ±{:g} A: not a gyro's current (a unit slip, or a "
                                     "damaged line?)",
                                     i, kMaxCurrent_A),
                         r.context(c.current, {"current"}));
      if (!f->series.time_s.empty() && !(t > f->series.time_s.back()))
        throw InputError(
            fmt::format("time does not increase ({} s after {} s)", t, f->series.time_s.back()),
            r.context(c.time, {"time"}));
      f->series.time_s.push_back(t);
      f->series.current_A.push_back(i);
      f->lines.push_back(r.line());
    }
  }
}

std::unique_ptr<std::istream> open(const std::string& path) {
  if (path == "-") return nullptr;
  detail::check_readable_path(path);
  auto f = std::make_unique<std::ifstream>(path);
  if (!*f) throw IoError("cannot open input file", {path, {}, ""});
  return f;
}

std::string comment_lines(const std::string& text) {
  std::string out;
  std::size_t b = 0;
  while (b < text.size()) {
    std::size_t e = text.find('\n', b);
    if (e == std::string::npos) e = text.size();
    out += "# " + text.substr(b, e - b) + "\n";
    b = e + 1;
  }
  return out;
}

}  // namespace

MaglevSeriesFile read_maglev_series(std::istream& in, const std::string& source, int position) {
  RecordReader rr(in, source);
  const Columns c = series_columns(rr);
  MaglevSeriesFile f;
  f.file = source;
  read_into(rr, c, position, &f, nullptr);
  if (f.series.current_A.empty())
    throw InputError("the file has no samples", {source, {}, "current"});
  return f;
}

MaglevSeriesFile read_maglev_series_file(const std::string& path, int position) {
  auto f = open(path);
  return read_maglev_series(f ? *f : std::cin, path == "-" ? "<stdin>" : path, position);
}

std::pair<MaglevSeriesFile, MaglevSeriesFile> read_maglev_two_positions(const std::string& path) {
  auto fs = open(path);
  const std::string source = path == "-" ? "<stdin>" : path;
  RecordReader rr(fs ? *fs : std::cin, source);
  const Columns c = series_columns(rr);
  if (!c.position)
    throw InputError(
        "one file for both positions needs a `position` column (or give one file per position)",
        {source, {}, "position"});
  std::pair<MaglevSeriesFile, MaglevSeriesFile> p;
  p.first.file = p.second.file = source;
  read_into(rr, c, 0, &p.first, &p.second);
  if (p.first.series.current_A.empty())
    throw InputError("position 1 has no samples", {source, {}, "position"});
  if (p.second.series.current_A.empty())
    throw InputError("position 2 has no samples", {source, {}, "position"});
  return p;
}

maglev::CalibrationInput read_maglev_calibration_table(const std::string& path) {
  auto fs = open(path);
  const std::string source = path == "-" ? "<stdin>" : path;
  RecordReader rr(fs ? *fs : std::cin, source);
  std::size_t col[5] = {0, 1, 2, 3, 4};
  const char* names[5] = {"azimuth", "mean1", "sigma1", "mean2", "sigma2"};
  if (!rr.header().empty()) {
    bool all = true;
    for (int k = 0; k < 5; ++k) all = all && rr.find_column(names[k]).has_value();
    if (all)
      for (int k = 0; k < 5; ++k) col[k] = *rr.find_column(names[k]);
  }
  // Every column's unit applies (azimuth: deg, dms, gon, rad, mrad; currents: A, mA, uA).
  double scale[5] = {1.0, 1.0, 1.0, 1.0, 1.0};
  AzimuthUnit az_unit = AzimuthUnit::Dms;
  if (!rr.header().empty()) {
    az_unit = azimuth_unit(rr, col[0]);
    for (int k = 1; k < 5; ++k) scale[k] = unit_scale(rr, col[k], names[k], true);
  }
  maglev::CalibrationInput in;
  RecordChunk chunk;
  while (rr.next(chunk, 4096)) {
    for (std::size_t k = 0; k < chunk.size(); ++k) {
      const Record r = chunk[k];
      if (r.size() < 5)
        throw InputError(
            fmt::format("expected 5 columns (azimuth, mean1, sigma1, mean2, sigma2), got {}",
                        r.size()),
            r.context());
      maglev::CalibrationSetup s;
      s.azimuth_rad = read_azimuth(r, col[0], az_unit);
      s.mean1_A = {r.number(col[1], {"mean1"}) * scale[1], r.number(col[2], {"sigma1"}) * scale[2]};
      s.mean2_A = {r.number(col[3], {"mean2"}) * scale[3], r.number(col[4], {"sigma2"}) * scale[4]};
      if (!(s.mean1_A.sigma > 0.0))
        throw InputError("sigma1 must be > 0", r.context(col[2], {"sigma1"}));
      if (!(s.mean2_A.sigma > 0.0))
        throw InputError("sigma2 must be > 0", r.context(col[4], {"sigma2"}));
      in.setups.push_back(s);
    }
  }
  if (in.setups.empty()) throw InputError("the table has no set-ups", {source, {}, "azimuth"});
  return in;
}

std::string maglev_series_csv(const maglev::PositionSeries& s, const std::string& header_comment) {
  std::string out = comment_lines(header_comment);
  out += "time [s],current [A]\n";
  for (std::size_t i = 0; i < s.current_A.size(); ++i)
    out += fmt::format("{:.17g},{:.17g}\n", s.time_s[i], s.current_A[i]);
  return out;
}

std::string maglev_two_position_csv(const maglev::PositionSeries& p1,
                                    const maglev::PositionSeries& p2,
                                    const std::string& header_comment) {
  std::string out = comment_lines(header_comment);
  out += "time [s],current [A],position\n";
  // In time order (the blocks of a 1-2-1 sequence as measured); position 1 first on a tie.
  std::size_t i = 0, j = 0;
  while (i < p1.current_A.size() || j < p2.current_A.size()) {
    if (j >= p2.current_A.size() || (i < p1.current_A.size() && p1.time_s[i] <= p2.time_s[j])) {
      out += fmt::format("{:.17g},{:.17g},1\n", p1.time_s[i], p1.current_A[i]);
      ++i;
    } else {
      out += fmt::format("{:.17g},{:.17g},2\n", p2.time_s[j], p2.current_A[j]);
      ++j;
    }
  }
  return out;
}

std::string maglev_calibration_csv(const maglev::CalibrationInput& in,
                                   const std::string& header_comment) {
  std::string out = comment_lines(header_comment);
  out += "azimuth [deg],mean1 [A],sigma1 [A],mean2 [A],sigma2 [A]\n";
  for (const auto& s : in.setups)
    out += fmt::format("{:.10f},{:.12g},{:.4g},{:.12g},{:.4g}\n", units::rad_to_deg(s.azimuth_rad),
                       s.mean1_A.value, s.mean1_A.sigma, s.mean2_A.value, s.mean2_A.sigma);
  return out;
}

std::string maglev_truth_comment(const std::string& made_by, const maglev::TwoPositionTruth& t) {
  return fmt::format(
      "made by: {}\ntruth: alpha1 {:.6f} deg, K {} A*s/rad, b {} A, latitude {:.6f} deg, r1 {:.6f} "
      "deg",
      made_by, units::rad_to_deg(t.alpha1_rad), t.scale_A_s_per_rad, t.bias_A,
      units::rad_to_deg(t.latitude_rad), units::rad_to_deg(t.circle_reading1_rad));
}

MaglevConstants read_maglev_constants(const std::string& path) {
  const Node root = Node::load_file(path);
  MaglevConstants c;
  const bool calibration =
      root.has("kind") && root.require("kind").string() == "maglev-calibration";
  if (!calibration)
    root.allow_only({"scale_A_s_per_rad", "scale_sigma_A_s_per_rad", "latitude", "circle_reading1",
                     "constant_deviation_A", "constant_deviation_sigma_A"});
  // io::Node's errors name file, line and key.
  if (auto k = root.get("scale_A_s_per_rad")) {
    Uncertain u{k->positive_number(), 0.0};
    if (auto s = root.get("scale_sigma_A_s_per_rad")) u.sigma = s->non_negative_number();
    c.scale_A_s_per_rad = u;
  }
  if (auto l = root.get("latitude")) c.latitude_rad = l->angle().rad();
  if (auto r = root.get("circle_reading1")) c.circle_reading1_rad = r->angle().rad();
  if (auto b = root.get("constant_deviation_A")) {
    Uncertain u{b->number(), 0.0};
    if (auto s = root.get("constant_deviation_sigma_A")) u.sigma = s->non_negative_number();
    c.constant_deviation_A = u;
  }
  return c;
}

}  // namespace meridian::io
