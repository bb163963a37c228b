// The navigation configuration, the NMEA 0183 adapter and the runner (io/nav_files.hpp).
#include <algorithm>
#include <array>
#include <iterator>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <tuple>
#include <string>
#include <system_error>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Core>
#include <fmt/format.h>

#include "meridian/core/atomic_file.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/geodesy/ellipsoid.hpp"
#include "meridian/io/nav_files.hpp"
#include "meridian/io/nmea.hpp"

namespace meridian::io {
namespace {
// Unity builds put this file beside the other io_nav sources: every helper lives in navj.
namespace navj {

constexpr double kDeg = units::kDegree;
constexpr double kDay_s = 86400.0;

std::string resolve(const std::string& config_path, const std::string& file) {
  const std::filesystem::path p = file;
  return (p.is_absolute() ? p : std::filesystem::path(config_path).parent_path() / p).string();
}

NavPosition node_position(const Node& n, std::optional<double>& sigma) {
  n.allow_only({"x_m", "y_m", "lat", "lon", "sigma_m"});
  NavPosition p;
  const bool plane = n.has("x_m") || n.has("y_m"), geo = n.has("lat") || n.has("lon");
  if (plane && geo) n.fail("give x_m, y_m or lat, lon, not both");
  if (!plane && !geo) n.fail("give x_m, y_m (plane, x north) or lat, lon");
  if (geo) {
    p.geographic = true;
    const Node lat = n.require("lat");
    p.lat_rad = lat.angle().rad();
    if (!(std::abs(p.lat_rad) <= units::kPi / 2)) lat.fail("latitude beyond ±90°");
    p.lon_rad = n.require("lon").angle().rad();
  } else {
    p.x_north_m = n.require("x_m").number();
    p.y_east_m = n.require("y_m").number();
  }
  if (auto s = n.get("sigma_m")) sigma = s->positive_number();
  return p;
}

geodesy::GridDefinition node_projection(const Node& n) {
  n.allow_only({"type", "zone", "north", "central_meridian", "scale_factor", "false_easting_m",
                "false_northing_m", "ellipsoid"});
  const geodesy::Ellipsoid e = [&] {
    if (auto el = n.get("ellipsoid")) {
      try {
        return geodesy::ellipsoid_by_name(el->string());
      } catch (Error& err) {
        el->fail(err.message());
      }
    }
    return geodesy::wgs84();
  }();
  const Node type = n.require("type");
  const std::string t = type.string();
  try {
    if (t == "utm") {
      n.allow_only({"type", "zone", "north", "ellipsoid"});
      const bool north = n.get("north") ? n.get("north")->boolean() : true;
      return geodesy::utm(n.require("zone").integer(), north, e);
    }
    if (t == "gauss-kruger-3" || t == "gauss-kruger-6") {
      n.allow_only({"type", "zone", "ellipsoid"});
      const int z = n.require("zone").integer();
      return t == "gauss-kruger-3" ? geodesy::gauss_kruger_3(z, e) : geodesy::gauss_kruger_6(z, e);
    }
  } catch (Error& err) {
    if (err.context().file.empty()) n.require("zone").fail(err.message());
    throw;
  }
  if (t != "transverse-mercator")
    type.fail(fmt::format("\"{}\" is not a projection type (utm, gauss-kruger-3, gauss-kruger-6, "
                          "transverse-mercator)",
                          t));
  n.allow_only({"type", "central_meridian", "scale_factor", "false_easting_m", "false_northing_m", "ellipsoid"});
  geodesy::GridDefinition g;
  g.system = geodesy::ZoneSystem::Custom;
  g.ellipsoid = e;
  g.central_meridian_rad = n.require("central_meridian").angle().rad();
  g.scale_factor = n.get("scale_factor") ? n.get("scale_factor")->positive_number() : 1.0;
  g.false_easting_m = n.get("false_easting_m") ? n.get("false_easting_m")->number() : 0.0;
  g.false_northing_m = n.get("false_northing_m") ? n.get("false_northing_m")->number() : 0.0;
  return g;
}

}  // namespace navj
}  // namespace

NavConfig read_nav_config(const std::string& path) {
  const Node root = Node::load_file(path);
  root.allow_only({"dr", "stations", "lops", "fixes", "truth", "nmea", "initial", "projection",
                   "sigma_speed_m_s", "sigma_heading_deg", "sigma_velocity_m_s", "chains", "rejection",
                   "threshold_m", "alpha", "segment_s", "bias_start_s", "backward_window_s", "fix_tolerance_m",
                   "max_reduction_s", "max_dr_gap_s", "sequential_sigma_velocity_m_s", "bias_model",
                   "bias_sigma_m_s", "bias_random_walk_m_s_per_sqrt_s", "bias_correlation_time_s",
                   "statistics_bin_s", "warn_gap_s"});
  NavConfig c;
  c.file = path;
  const auto file_key = [&](const char* key, std::string& out) {
    if (auto n = root.get(key)) {
      const std::string f = n->string();
      if (f.empty()) n->fail("empty file name");
      out = navj::resolve(path, f);
    }
  };
  file_key("dr", c.dr_path);
  file_key("stations", c.stations_path);
  file_key("lops", c.lops_path);
  file_key("fixes", c.fixes_path);
  file_key("truth", c.truth_path);
  if (auto n = root.get("nmea")) {
    if (root.has("dr")) n->fail("give dr: or nmea:, not both (both give the dead reckoning)");
    n->allow_only({"heading", "speed", "positions", "speed_sentence", "fix_interval_s", "sigma_fix_m",
                   "accept_missing_checksum"});
    NavNmeaConfig m;
    m.heading_path = navj::resolve(path, n->require("heading").string());
    m.speed_path = n->get("speed") ? navj::resolve(path, n->get("speed")->string()) : m.heading_path;
    m.positions_path = m.speed_path;
    if (auto p = n->get("positions")) {
      const std::string v = p->string();
      m.positions_path = v == "none" ? std::string() : navj::resolve(path, v);
    }
    if (auto s = n->get("speed_sentence")) {
      const std::string v = s->string();
      if (v == "vtg" || v == "VTG")
        m.speed_sentence = NavSpeedSentence::Vtg;
      else if (v == "vbw" || v == "VBW")
        m.speed_sentence = NavSpeedSentence::Vbw;
      else
        s->fail(fmt::format("\"{}\" is not a speed sentence (vtg, vbw)", v));
    }
    if (auto v = n->get("fix_interval_s")) m.fix_interval_s = v->non_negative_number();
    if (auto v = n->get("sigma_fix_m")) m.sigma_fix_m = v->positive_number(), m.sigma_fix_given = true;
    if (auto v = n->get("accept_missing_checksum")) m.accept_missing_checksum = v->boolean();
    if (m.positions_path.empty() && m.fix_interval_s > 0.0)
      n->get("fix_interval_s")->fail("fix_interval_s needs positions (GGA)");
    c.nmea = m;
  }
  if (c.dr_path.empty() && !c.nmea)
    root.fail("give the dead reckoning: dr: FILE.csv or an nmea: block");
  if (c.nmea && root.has("fixes") && !c.nmea->positions_path.empty())
    root.require("fixes").fail("the nmea: block gives the fixes (GGA): set its positions: none to use fixes:");
  if (c.nmea && root.has("truth") && c.nmea->fix_interval_s > 0.0)
    root.require("truth").fail("the nmea: block's fix_interval_s gives the truth (the withheld GGA)");
  if (c.lops_path.empty() != c.stations_path.empty())
    root.fail(c.lops_path.empty() ? "stations: without lops: (the stations serve the LOPs)"
                                  : "lops: needs stations: (the file of the stations the LOPs name)");
  if (auto n = root.get("initial")) c.initial = navj::node_position(*n, c.initial_sigma_m);
  if (auto n = root.get("projection")) c.projection = NavProjectionConfig{navj::node_projection(*n)};
  if (auto n = root.get("sigma_speed_m_s")) c.sigma_speed_m_s = n->non_negative_number();
  if (auto n = root.get("sigma_heading_deg")) c.sigma_heading_rad = n->non_negative_number() * navj::kDeg;
  if (auto n = root.get("sigma_velocity_m_s")) c.sigma_velocity_m_s = n->non_negative_number();
  if (auto n = root.get("chains")) {
    std::map<std::string, int> names;
    for (const Node& e : n->elements()) {
      e.allow_only({"name", "estimate_scale", "estimate_offset", "sigma_scale_prior", "sigma_offset_prior_m",
                    "propagation_speed_m_s"});
      NavChainConfig ch;
      const Node name = e.require("name");
      ch.chain.name = name.string();
      if (ch.chain.name.empty()) name.fail("a chain needs a name");
      if (auto [it, fresh] = names.emplace(ch.chain.name, name.line()); !fresh)
        name.fail(fmt::format("chain \"{}\" is already defined on line {}", ch.chain.name, it->second));
      if (auto v = e.get("estimate_scale")) ch.chain.estimate_scale = v->boolean();
      if (auto v = e.get("estimate_offset")) ch.chain.estimate_offset = v->boolean();
      if (auto v = e.get("sigma_scale_prior")) ch.chain.sigma_scale_prior = v->positive_number();
      if (auto v = e.get("sigma_offset_prior_m")) ch.chain.sigma_offset_prior_m = v->positive_number();
      if (auto v = e.get("propagation_speed_m_s")) ch.propagation_speed_m_s = v->positive_number();
      c.chains.push_back(ch);
    }
  }
  nav::Options& o = c.options;
  if (auto n = root.get("rejection")) {
    const std::string v = n->string();
    if (v == "threshold")
      o.rejection = nav::Rejection::Threshold;
    else if (v == "w-test")
      o.rejection = nav::Rejection::WTest;
    else
      n->fail(fmt::format("\"{}\" is not a rejection (threshold, w-test)", v));
  }
  if (auto n = root.get("threshold_m")) o.threshold_m = n->positive_number();
  if (auto n = root.get("alpha")) {
    o.alpha = n->positive_number();
    if (!(o.alpha < 1.0)) n->fail("alpha must be in (0, 1)");
  }
  if (auto n = root.get("segment_s")) o.segment_s = n->positive_number();
  if (auto n = root.get("bias_start_s")) o.bias_start_s = n->non_negative_number();
  if (auto n = root.get("backward_window_s")) o.backward_window_s = n->non_negative_number();
  if (auto n = root.get("fix_tolerance_m")) o.fix_tolerance_m = n->positive_number();
  if (auto n = root.get("max_reduction_s")) o.max_reduction_s = n->non_negative_number();
  if (auto n = root.get("max_dr_gap_s")) o.max_dr_gap_s = n->positive_number();
  if (auto n = root.get("sequential_sigma_velocity_m_s"))
    o.sequential_sigma_velocity_m_s = n->non_negative_number();
  if (auto n = root.get("bias_model")) {
    const std::string v = n->string();
    if (v == "random-walk")
      o.bias_model = nav::BiasModel::RandomWalk;
    else if (v == "gauss-markov")
      o.bias_model = nav::BiasModel::GaussMarkov;
    else
      n->fail(fmt::format("\"{}\" is not a bias model (random-walk, gauss-markov)", v));
  }
  if (auto n = root.get("bias_sigma_m_s")) o.bias_sigma_m_s = n->positive_number();
  if (auto n = root.get("bias_random_walk_m_s_per_sqrt_s"))
    o.bias_random_walk_m_s_per_sqrt_s = n->non_negative_number();
  if (auto n = root.get("bias_correlation_time_s")) o.bias_correlation_time_s = n->positive_number();
  if (auto n = root.get("statistics_bin_s")) o.statistics_bin_s = n->positive_number();
  if (auto n = root.get("warn_gap_s")) o.warn_gap_s = n->positive_number();
  c.lines = root.visited_lines();
  // The numerics' own range checks, at the key's line ("options.<name>" is the key <name>).
  try {
    nav::validate(o);
  } catch (Error& e) {
    const std::string& f = e.context().field;
    const std::string key = f.rfind("options.", 0) == 0 ? f.substr(8) : f;
    const auto it = c.lines.find(key);
    throw InputError(e.message(), {path, it == c.lines.end() ? std::optional<int>() : it->second, key});
  }
  return c;
}

std::string nav_simulation_config(const nav::SimulatedLine& line, const nav::SimulationOptions& so) {
  const nav::Input& in = line.input;
  std::string out = "# meridian nav process configuration, written by `meridian nav simulate`\n";
  if (!line.settings.empty()) {
    std::string one = line.settings.rfind("Simulated", 0) == 0 ? line.settings : "Simulated: " + line.settings;
    for (char& ch : one)
      if (ch == '\n' || ch == '\r') ch = ' ';
    out += "# " + one + "\n";
  }
  out += "dr: dr.csv\nstations: stations.csv\nlops: lops.csv\ntruth: truth.csv\n";
  if (!in.fixes.empty()) out += "fixes: fixes.csv\n";
  out += fmt::format("initial: {{x_m: {}, y_m: {}, sigma_m: {}}}\n", in.initial.x_north_m,
                     in.initial.y_east_m, in.initial.sigma_m);
  out += fmt::format("sigma_speed_m_s: {}\nsigma_heading_deg: {}\n", so.sigma_speed_m_s,
                     so.sigma_heading_rad / navj::kDeg);
  const nav::Options& o = in.options;
  out += fmt::format("rejection: {}\nthreshold_m: {}\nalpha: {}\nsegment_s: {}\nbias_start_s: {}\n"
                     "backward_window_s: {}\nfix_tolerance_m: {}\nmax_reduction_s: {}\n"
                     "max_dr_gap_s: {}\nsequential_sigma_velocity_m_s: {}\nbias_model: {}\nbias_sigma_m_s: {}\n"
                     "bias_random_walk_m_s_per_sqrt_s: {}\nbias_correlation_time_s: {}\n"
                     "statistics_bin_s: {}\nwarn_gap_s: {}\n",
                     o.rejection == nav::Rejection::WTest ? "w-test" : "threshold", o.threshold_m, o.alpha,
                     o.segment_s, o.bias_start_s, o.backward_window_s, o.fix_tolerance_m, o.max_reduction_s,
                     o.max_dr_gap_s, o.sequential_sigma_velocity_m_s,
                     o.bias_model == nav::BiasModel::GaussMarkov ? "gauss-markov" : "random-walk",
                     o.bias_sigma_m_s, o.bias_random_walk_m_s_per_sqrt_s, o.bias_correlation_time_s,
                     o.statistics_bin_s, o.warn_gap_s);
  if (!in.chains.empty()) {
    out += "chains:\n";
    for (const nav::Chain& ch : in.chains)
      out += fmt::format("  - {{name: \"{}\", estimate_scale: {}, estimate_offset: {}, sigma_scale_prior: {}, "
                         "sigma_offset_prior_m: {}}}\n",
                         ch.name, ch.estimate_scale, ch.estimate_offset, ch.sigma_scale_prior,
                         ch.sigma_offset_prior_m);
  }
  return out;
}

std::vector<std::string> write_nav_simulation(const std::string& dir, const nav::SimulatedLine& line,
                                              const nav::SimulationOptions& options) {
  const nav::Input& in = line.input;
  // Every file says what produced it: `# Simulated: <settings>`.
  const std::string settings =
      line.settings.rfind("Simulated", 0) == 0 ? line.settings : "Simulated: " + line.settings;
  // The files a user would bring, every one computed before any is written.
  std::vector<std::pair<std::string, std::string>> files = {
      {"dr.csv", nav_dr_csv(in.dr, settings)},
      {"stations.csv", nav_stations_csv(in.stations, settings)},
      {"lops.csv", nav_lops_csv(in, settings)},
      {"truth.csv", nav_truth_csv(in.truth, settings)},
  };
  if (!in.fixes.empty()) files.emplace_back("fixes.csv", nav_fixes_csv(in.fixes, settings));
  files.emplace_back("nav.yaml", nav_simulation_config(line, options));
  const std::filesystem::path d = dir;
  std::error_code ec;
  std::filesystem::create_directories(d, ec);
  if (ec || !std::filesystem::is_directory(d))
    throw IoError(fmt::format("cannot create the directory {}{}", dir, ec ? ": " + ec.message() : ""),
                  {dir, std::nullopt, {}});
  // All or none: every temporary exists before any is renamed into place.
  std::vector<std::unique_ptr<AtomicFileWriter>> writers;
  std::vector<std::string> names;
  for (const auto& [name, text] : files) {
    writers.push_back(std::make_unique<AtomicFileWriter>(d / name));
    writers.back()->write(text);
    names.push_back(name);
  }
  for (auto& w : writers) w->commit();
  return names;
}


// ---- NMEA 0183 ---------------------------------------------------------------------------------

namespace {
namespace navj {

/// One sentence the adapter uses, with its time candidates.
struct NmeaEvent {
  enum Kind { Heading, Speed, Position } kind = Heading;
  int line = 0;
  std::optional<double> dated_s;   // the reader's absolute time (dated time of day)
  std::optional<double> logger_s;  // the logger stamp
  std::optional<double> tod_s;     // the sentence's time of day
  double a = 0.0, b = 0.0;         // heading | speed, transverse | lat, lon
  bool valid = true;               // a usable value (else counted as skipped)
  std::string skip_reason;
  double time_s = 0.0;             // resolved
  bool timed = false;              // resolved to a time
  bool absolute = false;           // the time is absolute (dates or logger), not a bare time of day
};

struct Skips {
  std::map<std::string, std::pair<long, int>> by_reason;  // reason → count, first line
  void add(const std::string& file, const std::string& reason, int line) {
    auto& e = by_reason[file + ": " + reason];
    if (e.first++ == 0) e.second = line;
  }
};

struct NmeaFile {
  std::string path;
  std::vector<NmeaEvent> events;
  nmea::Summary summary;
  long rollover_corrected = 0;
};

NmeaFile read_events(const std::string& path, const NavNmeaConfig& c, bool heading, bool speed,
                     bool positions) {
  NmeaFile f;
  f.path = path;
  nmea::Options o;
  o.accept_missing_checksum = c.accept_missing_checksum;
  f.summary = nmea::read_file(path, o, [&](const nmea::Sentence& st) {
    NmeaEvent e;
    e.line = st.line;
    e.dated_s = st.time_s;
    e.logger_s = st.logger_time_s;
    if (heading) {
      if (const auto* h = std::get_if<nmea::Hdt>(&st.data)) {
        e.kind = NmeaEvent::Heading;
        e.valid = h->heading_rad.has_value();
        if (e.valid) e.a = *h->heading_rad;
        else e.skip_reason = "HDT without a heading";
        f.events.push_back(e);
        return;
      }
    }
    if (speed) {
      if (c.speed_sentence == NavSpeedSentence::Vtg) {
        if (const auto* v = std::get_if<nmea::Vtg>(&st.data)) {
          e.kind = NmeaEvent::Speed;
          e.valid = v->speed_m_s.has_value();
          if (e.valid) e.a = *v->speed_m_s;
          else e.skip_reason = "VTG without a speed";
          f.events.push_back(e);
          return;
        }
      } else if (const auto* v = std::get_if<nmea::Vbw>(&st.data)) {
        e.kind = NmeaEvent::Speed;
        e.valid = v->ground_longitudinal_m_s.has_value() && v->ground_valid.value_or(true);
        if (e.valid) {
          e.a = *v->ground_longitudinal_m_s;
          e.b = v->ground_transverse_m_s.value_or(0.0);
        } else {
          e.skip_reason = "VBW without a valid ground speed";
        }
        f.events.push_back(e);
        return;
      }
    }
    if (positions) {
      if (const auto* g = std::get_if<nmea::Gga>(&st.data)) {
        e.kind = NmeaEvent::Position;
        e.tod_s = g->time_of_day_s;
        const int q = g->fix_quality.value_or(1);
        if (!g->lat_rad || !g->lon_rad) e.valid = false, e.skip_reason = "GGA without a position";
        else if (!g->time_of_day_s) e.valid = false, e.skip_reason = "GGA without a time";
        else if (q == 0) e.valid = false, e.skip_reason = "GGA of an invalid fix (quality 0)";
        else if (q == 6) e.valid = false, e.skip_reason = "GGA of a dead-reckoning estimate (quality 6)";
        if (e.valid) e.a = *g->lat_rad, e.b = *g->lon_rad;
        f.events.push_back(e);
        return;
      }
    }
    // Other timed sentences (RMC, ZDA, GLL) carry the clock of a log without logger stamps.
    std::optional<double> tod;
    if (const auto* r = std::get_if<nmea::Rmc>(&st.data)) tod = r->time_of_day_s;
    if (const auto* z = std::get_if<nmea::Zda>(&st.data)) tod = z->time_of_day_s;
    if (const auto* g = std::get_if<nmea::Gll>(&st.data)) tod = g->time_of_day_s;
    if (const auto* g = std::get_if<nmea::Gga>(&st.data)) tod = g->time_of_day_s;
    if (tod) {
      e.kind = NmeaEvent::Position;
      e.tod_s = tod;
      e.valid = false;  // a clock only
      f.events.push_back(e);
    }
  });
  return f;
}

double nearest_day(double tod_s, double ref_s) {
  double t = std::floor(ref_s / kDay_s) * kDay_s + tod_s;
  if (t - ref_s > kDay_s / 2) t -= kDay_s;
  if (ref_s - t > kDay_s / 2) t += kDay_s;
  return t;
}

// Times of every event of a file: a dated time of day (a GPS week rollover against the logger
// stamp corrected), else the time of day on the day nearest the logger stamp or the nearest
// dated neighbour, else bare times of day unwrapped over midnight; sentences without a time
// (HDT, VTG, VBW) take the logger stamp, else the time of the last timed sentence before them.
void resolve_times(NmeaFile& f) {
  const double rollover_s = nmea::kGpsRolloverDays * kDay_s;
  std::optional<double> last_abs;
  std::vector<std::size_t> pending;  // timed events waiting for a reference
  for (std::size_t i = 0; i < f.events.size(); ++i) {
    NmeaEvent& e = f.events[i];
    if (!e.tod_s) continue;
    if (e.dated_s) {
      double t = *e.dated_s;
      if (e.logger_s && *e.logger_s - t >= (nmea::kGpsRolloverDays - 1) * kDay_s) {
        t += rollover_s * std::floor((*e.logger_s - t + kDay_s) / rollover_s);
        ++f.rollover_corrected;
      }
      e.time_s = t, e.timed = e.absolute = true;
    } else if (e.logger_s) {
      e.time_s = nearest_day(*e.tod_s, *e.logger_s), e.timed = e.absolute = true;
    } else if (last_abs) {
      e.time_s = nearest_day(*e.tod_s, *last_abs), e.timed = e.absolute = true;
    } else {
      pending.push_back(i);
      continue;
    }
    last_abs = e.time_s;
  }
  // Timed events before the first absolute time: the day of the first one after them.
  std::optional<double> next_abs;
  for (std::size_t k = f.events.size(); k-- > 0;) {
    NmeaEvent& e = f.events[k];
    if (e.tod_s && e.timed) next_abs = e.time_s;
    else if (e.tod_s && next_abs) e.time_s = nearest_day(*e.tod_s, *next_abs), e.timed = e.absolute = true, next_abs = e.time_s;
  }
  // No date or stamp at all: times of day from day 0, unwrapped over midnight.
  std::optional<double> last;
  for (NmeaEvent& e : f.events) {
    if (!e.tod_s || e.timed) continue;
    e.time_s = last ? nearest_day(*e.tod_s, *last) : *e.tod_s;
    e.timed = true, e.absolute = false;
    last = e.time_s;
  }
  // Untimed sentences.
  std::optional<std::pair<double, bool>> clock;
  for (NmeaEvent& e : f.events) {
    if (e.tod_s) {
      if (e.timed) clock = std::pair{e.time_s, e.absolute};
      continue;
    }
    if (e.logger_s) e.time_s = *e.logger_s, e.timed = e.absolute = true;
    else if (clock) e.time_s = clock->first, e.timed = true, e.absolute = clock->second;
  }
}

std::string count_text(long n, const char* one, const char* many) {
  return fmt::format("{} {}", n, n == 1 ? one : many);
}

std::string first_lines(const std::vector<int>& lines) {
  std::string out;
  for (std::size_t i = 0; i < std::min<std::size_t>(lines.size(), 3); ++i)
    out += (i ? ", " : "") + std::to_string(lines[i]);
  return fmt::format("{} {}", lines.size() == 1 ? "line" : "first lines", out);
}

// "; 1666 GPVTG sentences without a checksum were rejected (…)" when the sentences of `type`
// that a job needs were all dropped for that; empty otherwise.
std::string missing_checksum_hint(const nmea::Summary& s, const std::string& type) {
  if (s.accept_missing_checksum) return {};
  long n = 0;
  std::string names;
  for (const auto& [key, count] : s.no_checksum_by_type)
    if (key.size() == 5 && key.compare(2, 3, type) == 0) n += count, names += (names.empty() ? "" : "/") + key;
  if (n == 0) return {};
  return fmt::format("; {} {} {} without a checksum, rejected ({} of the file's {} without one): set "
                     "accept_missing_checksum: true in the nmea: block when the logger strips the checksums",
                     n, names, n == 1 ? "sentence" : "sentences", first_lines(s.no_checksum_lines),
                     s.no_checksum);
}

// What the NMEA reader dropped from a file (nothing is skipped silently): a warning with the
// counts by reason and the first lines; empty when nothing was dropped.
std::string dropped_lines_warning(const nmea::Summary& s) {
  std::vector<std::string> parts;
  if (s.bad_checksum > 0)
    parts.push_back(fmt::format("{} with a bad checksum ({})", s.bad_checksum, first_lines(s.bad_checksum_lines)));
  if (s.no_checksum > 0 && !s.accept_missing_checksum)
    parts.push_back(fmt::format("{} without a checksum ({}; accept_missing_checksum: true reads them)", s.no_checksum,
                                first_lines(s.no_checksum_lines)));
  if (s.malformed > 0) {
    std::string first;
    for (std::size_t i = 0; i < std::min<std::size_t>(s.malformed_lines.size(), 3); ++i)
      first += fmt::format("{}line {}: {}", i ? "; " : "", s.malformed_lines[i].first, s.malformed_lines[i].second);
    parts.push_back(fmt::format("{} malformed ({})", s.malformed, first));
  }
  if (parts.empty()) return {};
  long total = s.bad_checksum + s.malformed + (s.accept_missing_checksum ? 0 : s.no_checksum);
  std::string out = fmt::format("{}: {} not read: ", s.file, count_text(total, "line", "lines"));
  for (std::size_t i = 0; i < parts.size(); ++i) out += (i ? ", " : "") + parts[i];
  return out + " (meridian nav inspect lists them)";
}

}  // namespace navj
}  // namespace

NavNmeaData read_nav_nmea(const NavNmeaConfig& c) {
  using navj::NmeaEvent;
  // Each distinct file read once, for what it gives.
  std::vector<navj::NmeaFile> files;
  std::map<std::string, std::size_t> index;
  const auto want = [&](const std::string& p) {
    return std::tuple{p == c.heading_path, p == c.speed_path, !c.positions_path.empty() && p == c.positions_path};
  };
  for (const std::string& p : {c.heading_path, c.speed_path, c.positions_path}) {
    if (p.empty() || index.count(p)) continue;
    const auto [h, s, g] = want(p);
    index[p] = files.size();
    files.push_back(navj::read_events(p, c, h, s, g));
    navj::resolve_times(files.back());
  }
  NavNmeaData out;
  navj::Skips skips;
  // Absolute and bare times cannot share a scale.
  bool any_abs = false, any_bare = false;
  for (const auto& f : files)
    for (const NmeaEvent& e : f.events)
      if (e.timed && e.valid) (e.absolute ? any_abs : any_bare) = true;
  if (any_abs && any_bare) {
    std::string bare, abs;
    for (const auto& f : files) {
      bool b = false, a = false;
      for (const NmeaEvent& e : f.events)
        if (e.timed && e.valid) (e.absolute ? a : b) = true;
      if (b && bare.empty()) bare = f.path;
      if (a && abs.empty()) abs = f.path;
    }
    throw InputError(fmt::format("{} has times of day without a date (no ZDA, RMC or logger stamps) and {} has "
                                 "dated times: they cannot be put on one time scale",
                                 bare, abs),
                     {bare, std::nullopt, {}});
  }
  out.dated = !any_bare;
  for (auto& f : files) {
    if (std::string w = navj::dropped_lines_warning(f.summary); !w.empty()) out.warnings.push_back(std::move(w));
    if (f.summary.accept_missing_checksum && f.summary.no_checksum > 0)
      out.notes.push_back(fmt::format("{}: {} without a checksum read (accept_missing_checksum: true)", f.path,
                                      navj::count_text(f.summary.no_checksum, "sentence", "sentences")));
    if (f.rollover_corrected > 0)
      out.notes.push_back(fmt::format("{}: {} corrected for a GPS week rollover (dates 1024 weeks before the "
                                      "logger stamps)",
                                      f.path, navj::count_text(f.rollover_corrected, "time", "times")));
    else if (f.summary.gps_week_rollover_suspected)
      out.notes.push_back(fmt::format("{}: the dates look rolled over (GPS week rollover, line {}) and there are no "
                                      "logger stamps to correct them: check the times",
                                      f.path, f.summary.rollover_line.value_or(0)));
  }
  // Headings, sorted by time.
  std::vector<std::pair<double, double>> headings;
  for (const NmeaEvent& e : files[index.at(c.heading_path)].events) {
    if (e.kind != NmeaEvent::Heading) continue;
    if (!e.valid) skips.add(c.heading_path, e.skip_reason, e.line);
    else if (!e.timed) skips.add(c.heading_path, "HDT before any time (no logger stamp, no timed sentence)", e.line);
    else headings.emplace_back(e.time_s, e.a);
  }
  std::stable_sort(headings.begin(), headings.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  if (headings.empty()) {
    std::string why;
    for (const auto& [what, e] : skips.by_reason)
      if (what.rfind(c.heading_path + ": ", 0) == 0)
        why += fmt::format("; {} skipped: {} (first line {})", e.first, what.substr(c.heading_path.size() + 2), e.second);
    why += navj::missing_checksum_hint(files[index.at(c.heading_path)].summary, "HDT");
    throw InputError(fmt::format("no usable HDT heading (the nmea: block's heading file){}",
                                 why.empty() ? std::string("; the file has no HDT sentence") : why),
                     {c.heading_path, std::nullopt, {}});
  }
  // Speed samples with the heading interpolated circularly between its neighbours in time.
  struct SpeedSample {
    double t;
    double speed, heading;
    int line;
  };
  std::vector<SpeedSample> speeds;
  const char* sname = c.speed_sentence == NavSpeedSentence::Vtg ? "VTG" : "VBW";
  for (const NmeaEvent& e : files[index.at(c.speed_path)].events) {
    if (e.kind != NmeaEvent::Speed) continue;
    if (!e.valid) { skips.add(c.speed_path, e.skip_reason, e.line); continue; }
    if (!e.timed) { skips.add(c.speed_path, fmt::format("{} before any time", sname), e.line); continue; }
    const auto it = std::lower_bound(headings.begin(), headings.end(), e.time_s,
                                     [](const auto& h, double t) { return h.first < t; });
    const bool has_after = it != headings.end() && it->first - e.time_s <= kNavHeadingGap_s;
    const bool has_before = it != headings.begin() && e.time_s - std::prev(it)->first <= kNavHeadingGap_s;
    double h = 0.0;
    if (has_before && has_after) {
      const auto& [t0, h0] = *std::prev(it);
      const auto& [t1, h1] = *it;
      const double w = t1 > t0 ? (e.time_s - t0) / (t1 - t0) : 0.0;
      const double d = std::remainder(h1 - h0, 2.0 * units::kPi);
      h = h0 + w * d;
    } else if (has_before) {
      h = std::prev(it)->second;
    } else if (has_after) {
      h = it->second;
    } else {
      skips.add(c.speed_path, fmt::format("{} speed samples with no HDT within {} s", sname, kNavHeadingGap_s),
                e.line);
      continue;
    }
    // VBW: the transverse (starboard) component turns the velocity off the heading.
    const double speed = std::hypot(e.a, e.b);
    h += std::atan2(e.b, e.a);
    h = std::fmod(h, 2.0 * units::kPi);
    if (h < 0.0) h += 2.0 * units::kPi;
    speeds.push_back({e.time_s, speed, h, e.line});
  }
  std::stable_sort(speeds.begin(), speeds.end(), [](const auto& x, const auto& y) { return x.t < y.t; });
  if (speeds.empty()) {
    // Say why: the samples skipped (e.g. logs that do not overlap in time), or none at all.
    std::string why;
    for (const auto& [what, e] : skips.by_reason)
      if (what.rfind(c.speed_path + ": ", 0) == 0)
        why += fmt::format("; {} skipped: {} (first line {})", e.first, what.substr(c.speed_path.size() + 2), e.second);
    why += navj::missing_checksum_hint(files[index.at(c.speed_path)].summary, sname);
    if (why.empty())
      why = fmt::format("; the file has no {} sentence{}", sname,
                        c.speed_sentence == NavSpeedSentence::Vtg ? " (speed_sentence: vbw reads VBW)"
                                                                  : " (speed_sentence: vtg reads VTG)");
    throw InputError(fmt::format("no usable {} speed (the nmea: block's speed file){}", sname, why),
                     {c.speed_path, std::nullopt, {}});
  }
  // GGA positions, sorted; repeated times dropped.
  struct Pos {
    double t, lat, lon;
    int line;
  };
  std::vector<Pos> positions;
  if (!c.positions_path.empty()) {
    for (const NmeaEvent& e : files[index.at(c.positions_path)].events) {
      if (e.kind != NmeaEvent::Position || (!e.valid && e.skip_reason.empty())) continue;
      if (!e.valid) { skips.add(c.positions_path, e.skip_reason, e.line); continue; }
      positions.push_back({e.time_s, e.a, e.b, e.line});
    }
    std::stable_sort(positions.begin(), positions.end(), [](const auto& x, const auto& y) { return x.t < y.t; });
  }
  // The time origin: 00:00 UTC of the day of the earliest sample, a speed (the first DR epoch)
  // or a GGA position before it.
  const bool gga_first = !positions.empty() && positions.front().t < speeds.front().t;
  const double first = gga_first ? positions.front().t : speeds.front().t;
  out.origin_unix_s = std::floor(first / navj::kDay_s) * navj::kDay_s;
  out.notes.push_back(
      out.dated ? fmt::format("NMEA times: seconds since {} (00:00 UTC of the day of the earliest sample: {} of {} "
                              "line {}, {})",
                              nmea::iso8601_utc(out.origin_unix_s), gga_first ? "the GGA position" : "the speed",
                              gga_first ? c.positions_path : c.speed_path,
                              gga_first ? positions.front().line : speeds.front().line, nmea::iso8601_utc(first))
                : "NMEA times: seconds of the day of the first sentence (the logs have no date and "
                  "no logger stamps), unwrapped over midnight");
  out.dr.source = c.speed_path;
  out.dr.speed_heading = true;
  for (const SpeedSample& s : speeds) {
    const double t = s.t - out.origin_unix_s;
    if (!out.dr.records.empty() && !(t > out.dr.records.back().time_s)) {
      skips.add(c.speed_path, fmt::format("{} speed samples not after the previous one", sname), s.line);
      continue;
    }
    out.dr.records.push_back({t, s.speed, s.heading});
    out.dr.lines.push_back(s.line);
  }
  out.fixes.source = out.truth.source = c.positions_path;
  double next_fix = -1e300;
  for (std::size_t k = 0; k < positions.size(); ++k) {
    const Pos& p = positions[k];
    if (k > 0 && p.t == positions[k - 1].t) {
      skips.add(c.positions_path, "GGA repeating the time of the one before", p.line);
      continue;
    }
    NavPosition pos;
    pos.geographic = true, pos.lat_rad = p.lat, pos.lon_rad = p.lon;
    const double t = p.t - out.origin_unix_s;
    if (c.fix_interval_s <= 0.0 || p.t >= next_fix - 1e-3) {
      out.fixes.records.push_back({t, pos, c.sigma_fix_m, c.sigma_fix_m});
      out.fixes.lines.push_back(p.line);
      if (c.fix_interval_s > 0.0) next_fix = p.t + c.fix_interval_s;
    } else {
      out.truth.records.push_back({t, pos});
      out.truth.lines.push_back(p.line);
    }
  }
  if (!c.positions_path.empty()) {
    if (c.fix_interval_s > 0.0)
      out.notes.push_back(fmt::format("{}: one GGA position every {} s used as a fix ({}), the other {} withheld as "
                                      "the truth",
                                      c.positions_path, c.fix_interval_s, out.fixes.records.size(),
                                      out.truth.records.size()));
    out.notes.push_back(fmt::format("GGA fixes: sigma {} m per coordinate{}; HDOP is not used (a DOP is no sigma "
                                    "without the receiver's range error)",
                                    c.sigma_fix_m, c.sigma_fix_given ? "" : " (default; set nmea.sigma_fix_m)"));
  }
  if (c.speed_sentence == NavSpeedSentence::Vtg)
    out.notes.push_back("DR from the VTG speed over ground along the HDT heading (the VTG course is not used: a drift "
                        "angle goes into the estimated velocity bias)");
  for (const auto& [what, e] : skips.by_reason)
    out.notes.push_back(fmt::format("{}: {} skipped (first line {})", what, e.first, e.second));
  return out;
}


// ---- the runner ------------------------------------------------------------------------------

namespace {
namespace navj {

/// The job's plane: an optional grid.
struct Plane {
  std::shared_ptr<const geodesy::TransverseMercatorGrid> grid;
  geodesy::GridPoint forward(const NavPosition& p, const ErrorContext& where) const {
    if (!p.geographic) {
      geodesy::GridPoint g;
      g.x_north_m = p.x_north_m, g.y_east_m = p.y_east_m;
      if (grid) {
        try {
          const geodesy::GeographicPoint q = grid->reverse(p.x_north_m, p.y_east_m);
          g.convergence_rad = q.convergence_rad, g.scale = q.scale;
        } catch (Error& e) {
          throw InputError(e.message(), where);
        }
      }
      return g;
    }
    try {
      return grid->forward(p.lat_rad, p.lon_rad);
    } catch (Error& e) {
      throw InputError(e.message(), where);
    }
  }
};

/// Rotation of a true (north, east) vector into the grid with the scale: k·R(−γ).
Eigen::Matrix2d to_grid(double gamma, double k) {
  const double c = std::cos(gamma), s = std::sin(gamma);
  Eigen::Matrix2d m;
  m << c, s, -s, c;
  return k * m;
}

std::vector<NavSourceLine> source_lines(const std::string& file, const std::vector<int>& lines) {
  std::vector<NavSourceLine> out;
  out.reserve(lines.size());
  for (int l : lines) out.push_back({file, l});
  return out;
}

}  // namespace navj
}  // namespace

NavRun read_nav_job(const NavConfig& c) {
  NavRun run;
  std::vector<std::string>& notes = run.notes;
  // 1. The files, as written.
  NavDrFile dr;
  NavStationsFile stations;
  NavLopsFile lops;
  NavFixesFile fixes;
  NavTruthFile truth;
  bool nmea_job = false;
  if (c.nmea) {
    NavNmeaData d = read_nav_nmea(*c.nmea);
    dr = std::move(d.dr);
    if (!c.nmea->positions_path.empty()) fixes = std::move(d.fixes);
    if (c.nmea->fix_interval_s > 0.0) truth = std::move(d.truth);
    notes.insert(notes.end(), d.notes.begin(), d.notes.end());
    run.warnings.insert(run.warnings.end(), d.warnings.begin(), d.warnings.end());
    nmea_job = true;
  } else {
    dr = read_nav_dr_file(c.dr_path);
  }
  if (!c.stations_path.empty()) stations = read_nav_stations_file(c.stations_path);
  if (!c.lops_path.empty()) lops = read_nav_lops_file(c.lops_path);
  if (!c.fixes_path.empty()) fixes = read_nav_fixes_file(c.fixes_path);
  if (!c.truth_path.empty()) truth = read_nav_truth_file(c.truth_path);
  if (dr.records.size() < 2)
    throw InputError(fmt::format("{} DR sample{}: a line needs at least 2", dr.records.size(),
                                 dr.records.size() == 1 ? "" : "s"),
                     {dr.source, std::nullopt, {}});

  // 2. The plane: the configuration's projection, else a local transverse Mercator when any
  // position is geographic; plane and geographic positions together need a projection.
  const std::string* first_geo_file = nullptr;
  const std::string* first_plane_file = nullptr;
  std::optional<double> first_geo_lon;
  const auto kind = [&](const std::string& file, const NavPosition& p) {
    if (p.geographic) {
      if (!first_geo_file) first_geo_file = &file, first_geo_lon = p.lon_rad;
    } else if (!first_plane_file) {
      first_plane_file = &file;
    }
  };
  const std::string initial_name = c.file + " (initial:)";
  if (c.initial) kind(initial_name, *c.initial);
  for (const auto& p : stations.positions) kind(stations.source, p);
  for (const auto& f : fixes.records) kind(fixes.source, f.position);
  for (const auto& t : truth.records) kind(truth.source, t.position);
  navj::Plane plane;
  if (c.projection) {
    plane.grid = std::make_shared<geodesy::TransverseMercatorGrid>(c.projection->definition);
    notes.push_back("plane: " + geodesy::describe(c.projection->definition));
  } else if (first_geo_file && first_plane_file) {
    InputError e(fmt::format("{} gives plane coordinates (x_m, y_m) and {} geographic ones (lat, lon): give a "
                             "projection: to put both in one plane",
                             *first_plane_file, *first_geo_file),
                 {"", std::nullopt, "projection"});
    locate_error(e, c.file, c.lines);
    throw e;
  } else if (first_geo_file) {
    geodesy::GridDefinition g;
    g.system = geodesy::ZoneSystem::Custom;
    g.central_meridian_rad = std::round(*first_geo_lon / navj::kDeg * 10.0) / 10.0 * navj::kDeg;
    g.scale_factor = 1.0;
    g.false_easting_m = g.false_northing_m = 0.0;
    plane.grid = std::make_shared<geodesy::TransverseMercatorGrid>(g);
    notes.push_back(fmt::format("plane: transverse Mercator on WGS84, central meridian {:.1f}° (the first "
                                "geographic position's longitude, {}, rounded to 0.1°), scale 1, false easting "
                                "and northing 0 (default: no projection: in the configuration)",
                                g.central_meridian_rad / navj::kDeg, *first_geo_file));
  }
  if (plane.grid) {
    run.projection = plane.grid->definition();
    run.to_geographic = [grid = plane.grid](double x, double y) {
      const geodesy::GeographicPoint q = grid->reverse(x, y);
      return std::array<double, 2>{q.lat_rad, q.lon_rad};
    };
  }
  nav::Input& in = run.input;
  in.options = c.options;

  // 3. Stations, chains, LOPs.
  std::map<std::string, std::size_t> station_index;
  for (std::size_t k = 0; k < stations.names.size(); ++k) {
    const geodesy::GridPoint g =
        plane.forward(stations.positions[k], {stations.source, stations.lines[k], "lat_deg, lon_deg"});
    in.stations.push_back({stations.names[k], g.x_north_m, g.y_east_m});
    station_index[stations.names[k]] = k;
  }
  run.station_lines = navj::source_lines(stations.source, stations.lines);
  std::map<std::string, std::size_t> chain_index;
  for (std::size_t k = 0; k < c.chains.size(); ++k) {
    in.chains.push_back(c.chains[k].chain);
    chain_index[c.chains[k].chain.name] = k;
  }
  const auto known = [](const auto& m) {
    std::string s;
    for (const auto& [name, i] : m) s += (s.empty() ? "" : ", ") + name;
    return s.empty() ? std::string("none") : s;
  };
  bool time_differences = false;
  std::set<double> speeds_used;
  for (std::size_t k = 0; k < lops.records.size(); ++k) {
    const NavLopsFile::Record& r = lops.records[k];
    const int line = lops.lines[k];
    nav::Lop l;
    l.time_s = r.time_s;
    l.type = r.kind == NavLopKind::Range ? nav::LopType::Range : nav::LopType::RangeDifference;
    const auto station = [&](const std::string& name, const char* column) {
      const auto it = station_index.find(name);
      if (it == station_index.end())
        throw InputError(fmt::format("unknown station \"{}\" ({} has {})", name, c.stations_path, known(station_index)),
                         {lops.source, line, column});
      return it->second;
    };
    l.station = station(r.station, "station");
    if (r.kind != NavLopKind::Range) l.station2 = station(r.station2, "station2");
    double speed = kNavLoranPropagationSpeed_m_s;
    if (!r.chain.empty()) {
      const auto it = chain_index.find(r.chain);
      if (it == chain_index.end())
        throw InputError(fmt::format("chain \"{}\" is not in the configuration's chains: ({})", r.chain,
                                     known(chain_index)),
                         {lops.source, line, "chain"});
      l.chain = it->second;
      speed = c.chains[it->second].propagation_speed_m_s;
    }
    l.value_m = r.value;
    if (r.kind == NavLopKind::TimeDifference) {
      l.value_m = speed * r.value * 1e-6;
      time_differences = true;
      speeds_used.insert(speed);
    }
    l.sigma_m = r.sigma_m;
    in.lops.push_back(l);
  }
  run.lop_lines = navj::source_lines(lops.source, lops.lines);
  if (time_differences) {
    std::string list;
    for (double v : speeds_used) list += (list.empty() ? "" : ", ") + fmt::format("{} m/s", v);
    notes.push_back(fmt::format("time differences (µs) converted to range differences with the propagation "
                                "speed {} (LORAN-C default {} m/s; a chain's propagation_speed_m_s overrides it); "
                                "no additional secondary factor is applied",
                                list, kNavLoranPropagationSpeed_m_s));
  }

  // 4. Fixes and truth in the plane: a geographic σ north/east rotated by −γ and scaled by k.
  for (std::size_t k = 0; k < fixes.records.size(); ++k) {
    const NavFixesFile::Record& r = fixes.records[k];
    const ErrorContext where{fixes.source, fixes.lines[k], nmea_job ? "" : "lat_deg, lon_deg"};
    const geodesy::GridPoint g = plane.forward(r.position, where);
    nav::Fix f;
    f.time_s = r.time_s;
    f.x_north_m = g.x_north_m, f.y_east_m = g.y_east_m;
    const Eigen::Vector2d var(r.sigma_north_m * r.sigma_north_m, r.sigma_east_m * r.sigma_east_m);
    if (r.position.geographic) {
      const Eigen::Matrix2d m = navj::to_grid(g.convergence_rad, g.scale);
      f.covariance = m * var.asDiagonal() * m.transpose();
      f.covariance = 0.5 * (f.covariance + f.covariance.transpose()).eval();
    } else {
      f.covariance = var.asDiagonal();
    }
    in.fixes.push_back(f);
  }
  run.fix_lines = navj::source_lines(fixes.source, fixes.lines);
  {
    std::vector<std::size_t> order(truth.records.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return truth.records[a].time_s < truth.records[b].time_s;
    });
    for (std::size_t k : order) {
      const NavTruthFile::Record& r = truth.records[k];
      const geodesy::GridPoint g = plane.forward(r.position, {truth.source, truth.lines[k], ""});
      in.truth.push_back({r.time_s, g.x_north_m, g.y_east_m});
      run.truth_lines.push_back({truth.source, truth.lines[k]});
    }
  }

  // 5. The initial position: the configuration's, else the first fix near the first DR epoch.
  const double t0 = dr.records.front().time_s;
  if (c.initial) {
    const auto it = c.lines.find("initial");
    const geodesy::GridPoint g =
        plane.forward(*c.initial, {c.file, it == c.lines.end() ? std::optional<int>() : it->second, "initial"});
    in.initial.x_north_m = g.x_north_m, in.initial.y_east_m = g.y_east_m;
    if (c.initial_sigma_m) {
      in.initial.sigma_m = *c.initial_sigma_m;
    } else {
      notes.push_back(fmt::format("initial position: sigma {} m per coordinate (default; set initial.sigma_m)",
                                  in.initial.sigma_m));
    }
  } else {
    std::optional<std::size_t> best;
    for (std::size_t k = 0; k < in.fixes.size(); ++k)
      if (std::abs(in.fixes[k].time_s - t0) <= kNavInitialFixWindow_s &&
          (!best || std::abs(in.fixes[k].time_s - t0) < std::abs(in.fixes[*best].time_s - t0)))
        best = k;
    if (!best) {
      InputError e(fmt::format("no fix within {} s of the first DR epoch (t = {} s, {} line {}): give initial: "
                               "{{x_m, y_m, sigma_m}} or {{lat, lon, sigma_m}}",
                               kNavInitialFixWindow_s, t0, dr.source, dr.lines.front()),
                   {c.file, std::nullopt, "initial"});
      throw e;
    }
    const nav::Fix& f = in.fixes[*best];
    // nav::process moves it by the DR to the first epoch; here it only starts the walk of the
    // grid convergence along the DR below.
    in.initial_fix = *best;
    in.initial.x_north_m = f.x_north_m, in.initial.y_east_m = f.y_east_m;
    run.initial_line = NavSourceLine{fixes.source, fixes.lines[*best]};
    notes.push_back(fmt::format("initial position: the fix of {} line {} (t = {:.3f} s, sigma {:.3g} m) moved by the "
                                "dead reckoning to the first DR epoch (t = {:.3f} s), its covariance grown by the DR's "
                                "over those {:.3f} s; that fix is not used again as an observation (default: no "
                                "initial: in the configuration)",
                                fixes.source, fixes.lines[*best], f.time_s,
                                std::sqrt(std::max(f.covariance(0, 0), f.covariance(1, 1))), t0,
                                std::abs(f.time_s - t0)));
  }

  // 6. Dead reckoning in the plane: with a projection, true headings and velocities turned by −γ
  // and scaled by k at the dead-reckoned position.
  // A σ key of the other DR kind would be silently ignored: an error, like an unknown key.
  const auto not_for_this_dr = [&](const char* key, const std::string& what) {
    const auto it = c.lines.find(key);
    throw InputError(fmt::format("{} does not apply here: {}", key, what),
                     {c.file, it == c.lines.end() ? std::optional<int>() : it->second, key});
  };
  if (dr.speed_heading && c.sigma_velocity_m_s)
    not_for_this_dr("sigma_velocity_m_s",
                    fmt::format("{} gives speed and heading{} (set sigma_speed_m_s and sigma_heading_deg); "
                                "sigma_velocity_m_s is for a DR file of v_north_m_s, v_east_m_s",
                                dr.source, nmea_job ? " (NMEA VTG/VBW with HDT)" : ""));
  if (!dr.speed_heading && (c.sigma_speed_m_s || c.sigma_heading_rad))
    not_for_this_dr(c.sigma_speed_m_s ? "sigma_speed_m_s" : "sigma_heading_deg",
                    fmt::format("{} gives velocity components v_north_m_s, v_east_m_s (set sigma_velocity_m_s); "
                                "sigma_speed_m_s and sigma_heading_deg are for a DR file of speed_m_s, "
                                "heading_deg",
                                dr.source));
  const double sigma_v = c.sigma_speed_m_s.value_or(kNavDefaultSigmaSpeed_m_s);
  const double sigma_h = c.sigma_heading_rad.value_or(kNavDefaultSigmaHeading_deg * navj::kDeg);
  const double sigma_c = c.sigma_velocity_m_s.value_or(kNavDefaultSigmaSpeed_m_s);
  if (dr.speed_heading) {
    if (!c.sigma_speed_m_s)
      notes.push_back(fmt::format("DR speed sigma {} m/s (default; set sigma_speed_m_s)", sigma_v));
    if (!c.sigma_heading_rad)
      notes.push_back(fmt::format("DR heading sigma {}° (default; set sigma_heading_deg)", kNavDefaultSigmaHeading_deg));
  } else if (!c.sigma_velocity_m_s) {
    notes.push_back(fmt::format("DR velocity sigma {} m/s per component (default; set sigma_velocity_m_s)", sigma_c));
  }
  if (plane.grid)
    notes.push_back("DR: true headings and velocities turned into the grid (T = alpha - gamma, speed times the point "
                    "scale k) along the dead-reckoned track");
  double x = in.initial.x_north_m, y = in.initial.y_east_m;
  std::vector<std::array<double, 3>> dr_track;  // t, x, y dead-reckoned (for the LOPs below)
  dr_track.reserve(dr.records.size());
  for (std::size_t k = 0; k < dr.records.size(); ++k) {
    const NavDrFile::Record& r = dr.records[k];
    const ErrorContext where{dr.source, dr.lines[k], nmea_job ? "" : (dr.speed_heading ? "heading_deg" : "v_north_m_s")};
    double gamma = 0.0, scale = 1.0;
    if (plane.grid) {
      try {
        const geodesy::GeographicPoint q = plane.grid->reverse(x, y);
        gamma = q.convergence_rad, scale = q.scale;
      } catch (Error& e) {
        throw InputError(fmt::format("the dead-reckoned position ({:.1f}, {:.1f}) m leaves the projection: {}", x, y,
                                     e.message()),
                         where);
      }
    }
    nav::DrSample s;
    try {
      if (dr.speed_heading) {
        s = nav::dr_from_speed_heading(r.time_s, r.a * scale, r.b - gamma, sigma_v * scale, sigma_h);
      } else {
        s.time_s = r.time_s;
        const Eigen::Vector2d v = navj::to_grid(gamma, scale) * Eigen::Vector2d(r.a, r.b);
        s.v_north_m_s = v.x(), s.v_east_m_s = v.y();
        s.covariance = Eigen::Matrix2d::Identity() * (sigma_c * sigma_c * scale * scale);
      }
    } catch (Error& e) {
      throw InputError(e.message(), where);
    }
    if (k > 0) {
      const double dt = r.time_s - dr.records[k - 1].time_s;
      x += dt * s.v_north_m_s, y += dt * s.v_east_m_s;
    }
    in.dr.push_back(s);
    dr_track.push_back({r.time_s, x, y});
  }
  run.dr_lines = navj::source_lines(dr.source, dr.lines);

  // 7. With a projection, LOPs measured on the ground become grid lengths: each distance d of
  // the ship to a station times the line scale factor k_line = (k_ship + 4·k_mid + k_station)/6
  // (Simpson's rule along the chord), the ship at its dead-reckoned position at the LOP's time.
  if (plane.grid && !in.lops.empty()) {
    const auto ship_at = [&](double t) {
      const auto it = std::lower_bound(dr_track.begin(), dr_track.end(), t,
                                       [](const std::array<double, 3>& p, double tt) { return p[0] < tt; });
      if (it == dr_track.begin()) return std::array<double, 2>{(*it)[1], (*it)[2]};
      if (it == dr_track.end()) return std::array<double, 2>{dr_track.back()[1], dr_track.back()[2]};
      const auto& a = *std::prev(it);
      const auto& b = *it;
      const double w = (t - a[0]) / (b[0] - a[0]);
      return std::array<double, 2>{a[1] + w * (b[1] - a[1]), a[2] + w * (b[2] - a[2])};
    };
    const auto scale_at = [&](double px, double py) { return plane.grid->reverse(px, py).scale; };
    double max_ppm = 0.0;
    for (std::size_t k = 0; k < in.lops.size(); ++k) {
      nav::Lop& l = in.lops[k];
      const auto p = ship_at(l.time_s);
      // (k_line − 1)·d for one station: the grid length minus the ground length.
      const auto excess = [&](std::size_t si) {
        const nav::Station& st = in.stations[si];
        const double kl = (scale_at(p[0], p[1]) + 4.0 * scale_at(0.5 * (p[0] + st.x_north_m), 0.5 * (p[1] + st.y_east_m)) +
                           scale_at(st.x_north_m, st.y_east_m)) / 6.0;
        max_ppm = std::max(max_ppm, std::abs(kl - 1.0) * 1e6);
        return std::pair{kl, (kl - 1.0) * std::hypot(p[0] - st.x_north_m, p[1] - st.y_east_m) / kl};
      };
      try {
        if (l.type == nav::LopType::Range) {
          const auto [kl, e] = excess(l.station);
          (void)e;
          l.value_m *= kl;
          l.sigma_m *= kl;
        } else {
          const auto [k1, e1] = excess(l.station);
          const auto [k2, e2] = excess(l.station2);
          l.value_m += e1 - e2;
          l.sigma_m *= 0.5 * (k1 + k2);
        }
      } catch (Error& e) {
        throw InputError("the dead-reckoned position at this LOP leaves the projection: " + e.message(),
                         {lops.source, lops.lines[k], {}});
      }
    }
    notes.push_back(fmt::format("LOPs reduced from ground to grid lengths with the line scale factor (Simpson's rule "
                                "over k at the ship's dead-reckoned position, the midpoint and the station; up to "
                                "{:.1f} ppm here)",
                                max_ppm));
  }
  return run;
}

namespace {
namespace navj {

/// "lops[12].value_m" → {"lops", 12, "value_m"}; "epoch 5" → {"dr", 5, ""}.
struct FieldRef {
  std::string array;
  std::size_t index = 0;
  std::string member;
};

std::optional<FieldRef> parse_field(const std::string& f) {
  FieldRef r;
  std::size_t i = 0;
  if (f.rfind("epoch ", 0) == 0) {
    r.array = "dr";
    i = 6;
  } else {
    const auto b = f.find('[');
    if (b == std::string::npos || b == 0) return std::nullopt;
    r.array = f.substr(0, b);
    i = b + 1;
  }
  std::string digits;
  while (i < f.size() && f[i] >= '0' && f[i] <= '9') digits += f[i++];
  if (digits.empty() || digits.size() > 18) return std::nullopt;
  r.index = static_cast<std::size_t>(std::stoull(digits));
  if (i < f.size() && f[i] == ']') ++i;
  if (i < f.size() && f[i] == '.') r.member = f.substr(i + 1);
  return r;
}

[[noreturn]] void rethrow_with(const Error& e, ErrorContext c) {
  const std::string msg = e.message();
  if (dynamic_cast<const ParseError*>(&e)) throw ParseError(msg, c);
  if (dynamic_cast<const InputError*>(&e)) throw InputError(msg, c);
  if (dynamic_cast<const NumericalError*>(&e)) throw NumericalError(msg, c);
  if (dynamic_cast<const IoError*>(&e)) throw IoError(msg, c);
  throw Error(msg, c);
}

/// The CSV column of an Input member as the user wrote it.
std::string column_of(const std::string& array, const std::string& member, bool nmea) {
  if (nmea && (array == "dr" || array == "fixes" || array == "truth")) return {};
  if (member == "value_m") return "value";
  if (member == "x_north_m") return "x_m";
  if (member == "y_east_m") return "y_m";
  if (member == "covariance") return array == "fixes" ? "sigma_m" : "";
  if (member == "v_north_m_s" || member == "v_east_m_s") return "";
  return member;
}

}  // namespace navj
}  // namespace

void throw_located_nav_error(const Error& e, const NavRun& run, const NavConfig& config) {
  const std::string& f = e.context().field;
  // An error that names a file already, or no field (nothing to locate), goes on as it is.
  if (!e.context().file.empty() || f.empty()) navj::rethrow_with(e, e.context());
  if (const auto ref = navj::parse_field(f)) {
    const std::vector<NavSourceLine>* table = nullptr;
    if (ref->array == "dr") table = &run.dr_lines;
    if (ref->array == "lops") table = &run.lop_lines;
    if (ref->array == "fixes") table = &run.fix_lines;
    if (ref->array == "stations") table = &run.station_lines;
    if (ref->array == "truth") table = &run.truth_lines;
    if (table && ref->index < table->size()) {
      const NavSourceLine& s = (*table)[ref->index];
      navj::rethrow_with(e, {s.file, s.line, navj::column_of(ref->array, ref->member, config.nmea.has_value())});
    }
  }
  if (f.rfind("initial", 0) == 0 && run.initial_line)
    navj::rethrow_with(e, {run.initial_line->file, run.initial_line->line, {}});
  // options.<name> is the configuration's key <name>.
  if (f.rfind("options.", 0) == 0) {
    const std::string key = f.substr(8);
    const auto it = config.lines.find(key);
    navj::rethrow_with(e, {config.file, it == config.lines.end() ? std::optional<int>() : it->second, key});
  }
  std::optional<int> line;
  std::size_t best = 0;
  for (const auto& [path, l] : config.lines) {
    const bool prefix = f.compare(0, path.size(), path) == 0 &&
                        (f.size() == path.size() || f[path.size()] == '.' || f[path.size()] == '[');
    if (prefix && path.size() >= best) best = path.size(), line = l;
  }
  navj::rethrow_with(e, {config.file, line, f});
}

NavRun run_nav(const NavConfig& config, Progress* progress) {
  NavRun run = read_nav_job(config);
  try {
    run.result = nav::process(run.input, progress);
  } catch (Error& e) {
    if (progress) progress->finish();
    throw_located_nav_error(e, run, config);
  }
  // Name the rejected and skipped observations by their file and line ("lops.csv:14").
  const auto source = [&](nav::RejectedObservation::Kind kind, std::size_t index) {
    const std::vector<NavSourceLine>& t = kind == nav::RejectedObservation::Kind::Lop ? run.lop_lines : run.fix_lines;
    if (index >= t.size()) return std::string();
    return fmt::format("{}:{}", std::filesystem::path(t[index].file).filename().string(), t[index].line);
  };
  for (nav::RejectedObservation& o : run.result.rejected) o.source = source(o.kind, o.index);
  for (nav::SkippedObservation& o : run.result.skipped) o.source = source(o.kind, o.index);
  run.result.notes.insert(run.result.notes.end(), run.notes.begin(), run.notes.end());
  run.result.warnings.insert(run.result.warnings.end(), run.warnings.begin(), run.warnings.end());
  return run;
}

}  // namespace meridian::io
