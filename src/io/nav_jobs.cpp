// The navigation configuration, the NMEA 0183 adapter, the job reader and the runner
// (io/nav_files.hpp).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <utility>
#include <variant>
#include <vector>

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

namespace {
namespace navj {

// The `nmea:` block (files relative to the configuration's directory `path`).
NavNmeaConfig node_nmea(const Node& n, const std::string& path) {
  n.allow_only({"heading", "speed", "positions", "speed_sentence", "fix_interval_s", "sigma_fix_m",
                "accept_missing_checksum"});
  NavNmeaConfig m;
  m.heading_path = resolve(path, n.require("heading").string());
  m.speed_path = n.get("speed") ? resolve(path, n.get("speed")->string()) : m.heading_path;
  m.positions_path = m.speed_path;
  if (auto p = n.get("positions")) {
    const std::string v = p->string();
    m.positions_path = v == "none" ? std::string() : resolve(path, v);
  }
  if (auto s = n.get("speed_sentence")) {
    const std::string v = s->string();
    if (v == "vtg" || v == "VTG")
      m.speed_sentence = NavSpeedSentence::Vtg;
    else if (v == "vbw" || v == "VBW")
      m.speed_sentence = NavSpeedSentence::Vbw;
    else
      s->fail(fmt::format("\"{}\" is not a speed sentence (vtg, vbw)", v));
  }
  if (auto v = n.get("fix_interval_s")) m.fix_interval_s = v->non_negative_number();
  if (auto v = n.get("sigma_fix_m")) m.sigma_fix_m = v->positive_number(), m.sigma_fix_given = true;
  if (auto v = n.get("accept_missing_checksum")) m.accept_missing_checksum = v->boolean();
  if (m.positions_path.empty() && m.fix_interval_s > 0.0)
    n.get("fix_interval_s")->fail("fix_interval_s needs positions (GGA)");
  return m;
}

// The input files: CSV paths or the `nmea:` block, and the combinations that make a job.
void input_files(const Node& root, const std::string& path, NavConfig& c) {
  const auto file_key = [&](const char* key, std::string& out) {
    if (auto n = root.get(key)) {
      const std::string f = n->string();
      if (f.empty()) n->fail("empty file name");
      out = resolve(path, f);
    }
  };
  file_key("dr", c.dr_path);
  file_key("stations", c.stations_path);
  file_key("lops", c.lops_path);
  file_key("fixes", c.fixes_path);
  file_key("truth", c.truth_path);
  if (auto n = root.get("nmea")) {
    if (root.has("dr")) n->fail("give dr: or nmea:, not both (both give the dead reckoning)");
    c.nmea = node_nmea(*n, path);
  }
  if (c.dr_path.empty() && !c.nmea) root.fail("give the dead reckoning: dr: FILE.csv or an nmea: block");
  if (c.nmea && root.has("fixes") && !c.nmea->positions_path.empty())
    root.require("fixes").fail("the nmea: block gives the fixes (GGA): set its positions: none to use fixes:");
  if (c.nmea && root.has("truth") && c.nmea->fix_interval_s > 0.0)
    root.require("truth").fail("the nmea: block's fix_interval_s gives the truth (the withheld GGA)");
  if (c.lops_path.empty() != c.stations_path.empty())
    root.fail(c.lops_path.empty() ? "stations: without lops: (the stations serve the LOPs)"
                                  : "lops: needs stations: (the file of the stations the LOPs name)");
}

// `chains:`, names unique.
std::vector<NavChainConfig> node_chains(const Node& n) {
  std::vector<NavChainConfig> chains;
  std::map<std::string, int> names;
  for (const Node& e : n.elements()) {
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
    chains.push_back(ch);
  }
  return chains;
}

// The choices among names: rejection and bias model.
void choice_options(const Node& root, nav::Options& o) {
  if (auto n = root.get("rejection")) {
    const std::string v = n->string();
    if (v == "threshold")
      o.rejection = nav::Rejection::Threshold;
    else if (v == "w-test")
      o.rejection = nav::Rejection::WTest;
    else
      n->fail(fmt::format("\"{}\" is not a rejection (threshold, w-test)", v));
  }
  if (auto n = root.get("bias_model")) {
    const std::string v = n->string();
    if (v == "random-walk")
      o.bias_model = nav::BiasModel::RandomWalk;
    else if (v == "gauss-markov")
      o.bias_model = nav::BiasModel::GaussMarkov;
    else
      n->fail(fmt::format("\"{}\" is not a bias model (random-walk, gauss-markov)", v));
  }
}

// The numeric options, each at its key (the numerics' range checks follow in read_nav_config).
void numeric_options(const Node& root, nav::Options& o) {
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
  if (auto n = root.get("sequential_sigma_velocity_m_s")) o.sequential_sigma_velocity_m_s = n->non_negative_number();
  if (auto n = root.get("bias_sigma_m_s")) o.bias_sigma_m_s = n->positive_number();
  if (auto n = root.get("bias_random_walk_m_s_per_sqrt_s")) o.bias_random_walk_m_s_per_sqrt_s = n->non_negative_number();
  if (auto n = root.get("bias_correlation_time_s")) o.bias_correlation_time_s = n->positive_number();
  if (auto n = root.get("statistics_bin_s")) o.statistics_bin_s = n->positive_number();
  if (auto n = root.get("warn_gap_s")) o.warn_gap_s = n->positive_number();
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
  navj::input_files(root, path, c);
  if (auto n = root.get("initial")) c.initial = navj::node_position(*n, c.initial_sigma_m);
  if (auto n = root.get("projection")) c.projection = NavProjectionConfig{navj::node_projection(*n)};
  if (auto n = root.get("sigma_speed_m_s")) c.sigma_speed_m_s = n->non_negative_number();
  if (auto n = root.get("sigma_heading_deg")) c.sigma_heading_rad = n->non_negative_number() * navj::kDeg;
  if (auto n = root.get("sigma_velocity_m_s")) c.sigma_velocity_m_s = n->non_negative_number();
  if (auto n = root.get("chains")) c.chains = navj::node_chains(*n);
  navj::choice_options(root, c.options);
  navj::numeric_options(root, c.options);
  c.lines = root.visited_lines();
  // The numerics' own range checks, at the key's line ("options.<name>" is the key <name>).
  SourceMap keys;
  keys.add_document("options", path, c.lines);
  located(keys, [&] { nav::validate(c.options); });
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

namespace {
namespace navj {

/// The distinct files of an `nmea:` block, each read once for what it gives.
struct NmeaFiles {
  std::vector<NmeaFile> files;
  std::map<std::string, std::size_t> index;
  const NmeaFile& at(const std::string& path) const { return files[index.at(path)]; }
};

NmeaFiles read_nmea_files(const NavNmeaConfig& c) {
  NmeaFiles out;
  for (const std::string& p : {c.heading_path, c.speed_path, c.positions_path}) {
    if (p.empty() || out.index.count(p)) continue;
    out.index[p] = out.files.size();
    out.files.push_back(read_events(p, c, p == c.heading_path, p == c.speed_path,
                                    !c.positions_path.empty() && p == c.positions_path));
    resolve_times(out.files.back());
  }
  return out;
}

// Absolute and bare times cannot share a scale: InputError naming a file of each. Returns
// whether the times are dated (absolute).
bool check_time_scale(const NmeaFiles& nf) {
  std::string bare, abs;
  for (const auto& f : nf.files) {
    bool b = false, a = false;
    for (const NmeaEvent& e : f.events)
      if (e.timed && e.valid) (e.absolute ? a : b) = true;
    if (b && bare.empty()) bare = f.path;
    if (a && abs.empty()) abs = f.path;
  }
  if (!bare.empty() && !abs.empty())
    throw InputError(fmt::format("{} has times of day without a date (no ZDA, RMC or logger stamps) and {} has "
                                 "dated times: they cannot be put on one time scale",
                                 bare, abs),
                     {bare, std::nullopt, {}});
  return bare.empty();
}

// What each file's reader dropped (warnings), accepted without a checksum and corrected (notes).
void file_notes(const NmeaFiles& nf, NavNmeaData& out) {
  for (const auto& f : nf.files) {
    if (std::string w = dropped_lines_warning(f.summary); !w.empty()) out.warnings.push_back(std::move(w));
    if (f.summary.accept_missing_checksum && f.summary.no_checksum > 0)
      out.notes.push_back(fmt::format("{}: {} without a checksum read (accept_missing_checksum: true)", f.path,
                                      count_text(f.summary.no_checksum, "sentence", "sentences")));
    if (f.rollover_corrected > 0)
      out.notes.push_back(fmt::format("{}: {} corrected for a GPS week rollover (dates 1024 weeks before the "
                                      "logger stamps)",
                                      f.path, count_text(f.rollover_corrected, "time", "times")));
    else if (f.summary.gps_week_rollover_suspected)
      out.notes.push_back(fmt::format("{}: the dates look rolled over (GPS week rollover, line {}) and there are no "
                                      "logger stamps to correct them: check the times",
                                      f.path, f.summary.rollover_line.value_or(0)));
  }
}

// "; N skipped: <reason> (first line L)" for every reason of `path`, then the missing-checksum
// hint for `type`: why a file gave no usable sample.
std::string why_none(const Skips& skips, const std::string& path, const nmea::Summary& s, const std::string& type) {
  std::string why;
  for (const auto& [what, e] : skips.by_reason)
    if (what.rfind(path + ": ", 0) == 0)
      why += fmt::format("; {} skipped: {} (first line {})", e.first, what.substr(path.size() + 2), e.second);
  return why + missing_checksum_hint(s, type);
}

/// HDT headings (time, heading), sorted by time.
using Headings = std::vector<std::pair<double, double>>;

Headings headings_of(const NavNmeaConfig& c, const NmeaFiles& nf, Skips& skips) {
  Headings headings;
  for (const NmeaEvent& e : nf.at(c.heading_path).events) {
    if (e.kind != NmeaEvent::Heading) continue;
    if (!e.valid) skips.add(c.heading_path, e.skip_reason, e.line);
    else if (!e.timed) skips.add(c.heading_path, "HDT before any time (no logger stamp, no timed sentence)", e.line);
    else headings.emplace_back(e.time_s, e.a);
  }
  std::stable_sort(headings.begin(), headings.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  if (headings.empty()) {
    const std::string why = why_none(skips, c.heading_path, nf.at(c.heading_path).summary, "HDT");
    throw InputError(fmt::format("no usable HDT heading (the nmea: block's heading file){}",
                                 why.empty() ? std::string("; the file has no HDT sentence") : why),
                     {c.heading_path, std::nullopt, {}});
  }
  return headings;
}

// The heading at time t interpolated circularly between its neighbours within kNavHeadingGap_s
// (the nearest one when only one side has one); nullopt when neither side has one.
std::optional<double> heading_at(const Headings& headings, double t) {
  const auto it = std::lower_bound(headings.begin(), headings.end(), t, [](const auto& h, double tt) { return h.first < tt; });
  const bool has_after = it != headings.end() && it->first - t <= kNavHeadingGap_s;
  const bool has_before = it != headings.begin() && t - std::prev(it)->first <= kNavHeadingGap_s;
  if (has_before && has_after) {
    const auto& [t0, h0] = *std::prev(it);
    const auto& [t1, h1] = *it;
    const double w = t1 > t0 ? (t - t0) / (t1 - t0) : 0.0;
    const double d = std::remainder(h1 - h0, 2.0 * units::kPi);
    return h0 + w * d;
  }
  if (has_before) return std::prev(it)->second;
  if (has_after) return it->second;
  return std::nullopt;
}

/// A speed sample with its heading.
struct SpeedSample {
  double t;
  double speed, heading;
  int line;
};

const char* speed_sentence_name(const NavNmeaConfig& c) {
  return c.speed_sentence == NavSpeedSentence::Vtg ? "VTG" : "VBW";
}

// Speed samples with the heading of their time, sorted by time.
std::vector<SpeedSample> speeds_of(const NavNmeaConfig& c, const NmeaFiles& nf, const Headings& headings,
                                   Skips& skips) {
  std::vector<SpeedSample> speeds;
  const char* sname = speed_sentence_name(c);
  for (const NmeaEvent& e : nf.at(c.speed_path).events) {
    if (e.kind != NmeaEvent::Speed) continue;
    if (!e.valid) { skips.add(c.speed_path, e.skip_reason, e.line); continue; }
    if (!e.timed) { skips.add(c.speed_path, fmt::format("{} before any time", sname), e.line); continue; }
    std::optional<double> h = heading_at(headings, e.time_s);
    if (!h) {
      skips.add(c.speed_path, fmt::format("{} speed samples with no HDT within {} s", sname, kNavHeadingGap_s),
                e.line);
      continue;
    }
    // VBW: the transverse (starboard) component turns the velocity off the heading.
    const double speed = std::hypot(e.a, e.b);
    *h += std::atan2(e.b, e.a);
    *h = std::fmod(*h, 2.0 * units::kPi);
    if (*h < 0.0) *h += 2.0 * units::kPi;
    speeds.push_back({e.time_s, speed, *h, e.line});
  }
  std::stable_sort(speeds.begin(), speeds.end(), [](const auto& x, const auto& y) { return x.t < y.t; });
  if (speeds.empty()) {
    // Say why: the samples skipped (e.g. logs that do not overlap in time), or none at all.
    std::string why = why_none(skips, c.speed_path, nf.at(c.speed_path).summary, sname);
    if (why.empty())
      why = fmt::format("; the file has no {} sentence{}", sname,
                        c.speed_sentence == NavSpeedSentence::Vtg ? " (speed_sentence: vbw reads VBW)"
                                                                  : " (speed_sentence: vtg reads VTG)");
    throw InputError(fmt::format("no usable {} speed (the nmea: block's speed file){}", sname, why),
                     {c.speed_path, std::nullopt, {}});
  }
  return speeds;
}

/// A GGA position.
struct GgaPosition {
  double t, lat, lon;
  int line;
};

// GGA positions, sorted by time.
std::vector<GgaPosition> positions_of(const NavNmeaConfig& c, const NmeaFiles& nf, Skips& skips) {
  std::vector<GgaPosition> positions;
  if (c.positions_path.empty()) return positions;
  for (const NmeaEvent& e : nf.at(c.positions_path).events) {
    if (e.kind != NmeaEvent::Position || (!e.valid && e.skip_reason.empty())) continue;
    if (!e.valid) { skips.add(c.positions_path, e.skip_reason, e.line); continue; }
    positions.push_back({e.time_s, e.a, e.b, e.line});
  }
  std::stable_sort(positions.begin(), positions.end(), [](const auto& x, const auto& y) { return x.t < y.t; });
  return positions;
}

// The time origin: 00:00 UTC of the day of the earliest sample, a speed (the first DR epoch)
// or a GGA position before it; with its note.
void time_origin(const NavNmeaConfig& c, const std::vector<SpeedSample>& speeds,
                 const std::vector<GgaPosition>& positions, NavNmeaData& out) {
  const bool gga_first = !positions.empty() && positions.front().t < speeds.front().t;
  const double first = gga_first ? positions.front().t : speeds.front().t;
  out.origin_unix_s = std::floor(first / kDay_s) * kDay_s;
  out.notes.push_back(
      out.dated ? fmt::format("NMEA times: seconds since {} (00:00 UTC of the day of the earliest sample: {} of {} "
                              "line {}, {})",
                              nmea::iso8601_utc(out.origin_unix_s), gga_first ? "the GGA position" : "the speed",
                              gga_first ? c.positions_path : c.speed_path,
                              gga_first ? positions.front().line : speeds.front().line, nmea::iso8601_utc(first))
                : "NMEA times: seconds of the day of the first sentence (the logs have no date and "
                  "no logger stamps), unwrapped over midnight");
}

// DR records from the origin, strictly increasing times.
void dr_records(const NavNmeaConfig& c, const std::vector<SpeedSample>& speeds, Skips& skips, NavNmeaData& out) {
  out.dr.source = c.speed_path;
  out.dr.speed_heading = true;
  for (const SpeedSample& s : speeds) {
    const double t = s.t - out.origin_unix_s;
    if (!out.dr.records.empty() && !(t > out.dr.records.back().time_s)) {
      skips.add(c.speed_path, fmt::format("{} speed samples not after the previous one", speed_sentence_name(c)),
                s.line);
      continue;
    }
    out.dr.records.push_back({t, s.speed, s.heading});
    out.dr.lines.push_back(s.line);
  }
}

// GGA fixes, one every fix_interval_s (every one with 0), the others withheld as truth.
void fix_and_truth_records(const NavNmeaConfig& c, const std::vector<GgaPosition>& positions, Skips& skips,
                           NavNmeaData& out) {
  out.fixes.source = out.truth.source = c.positions_path;
  double next_fix = -1e300;
  for (std::size_t k = 0; k < positions.size(); ++k) {
    const GgaPosition& p = positions[k];
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
}

// The notes of the adapter's choices: fixes and truth, σ of the fixes, VTG, the samples skipped.
void adapter_notes(const NavNmeaConfig& c, const Skips& skips, NavNmeaData& out) {
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
}

}  // namespace navj
}  // namespace

NavNmeaData read_nav_nmea(const NavNmeaConfig& c) {
  const navj::NmeaFiles files = navj::read_nmea_files(c);
  NavNmeaData out;
  navj::Skips skips;
  out.dated = navj::check_time_scale(files);
  navj::file_notes(files, out);
  const navj::Headings headings = navj::headings_of(c, files, skips);
  const std::vector<navj::SpeedSample> speeds = navj::speeds_of(c, files, headings, skips);
  const std::vector<navj::GgaPosition> positions = navj::positions_of(c, files, skips);
  navj::time_origin(c, speeds, positions, out);
  navj::dr_records(c, speeds, skips, out);
  navj::fix_and_truth_records(c, positions, skips, out);
  navj::adapter_notes(c, skips, out);
  return out;
}


// ---- the runner ------------------------------------------------------------------------------

namespace {
namespace navj {

/// The files of a job, as written.
struct JobFiles {
  NavDrFile dr;
  NavStationsFile stations;
  NavLopsFile lops;
  NavFixesFile fixes;
  NavTruthFile truth;
  std::vector<std::string> notes, warnings;  ///< of the NMEA adapter
};

JobFiles read_job_files(const NavConfig& c) {
  JobFiles f;
  if (c.nmea) {
    NavNmeaData d = read_nav_nmea(*c.nmea);
    f.dr = std::move(d.dr);
    if (!c.nmea->positions_path.empty()) f.fixes = std::move(d.fixes);
    if (c.nmea->fix_interval_s > 0.0) f.truth = std::move(d.truth);
    f.notes = std::move(d.notes);
    f.warnings = std::move(d.warnings);
  } else {
    f.dr = read_nav_dr_file(c.dr_path);
  }
  if (!c.stations_path.empty()) f.stations = read_nav_stations_file(c.stations_path);
  if (!c.lops_path.empty()) f.lops = read_nav_lops_file(c.lops_path);
  if (!c.fixes_path.empty()) f.fixes = read_nav_fixes_file(c.fixes_path);
  if (!c.truth_path.empty()) f.truth = read_nav_truth_file(c.truth_path);
  if (f.dr.records.size() < 2)
    throw InputError(fmt::format("{} DR sample{}: a line needs at least 2", f.dr.records.size(),
                                 f.dr.records.size() == 1 ? "" : "s"),
                     {f.dr.source, std::nullopt, {}});
  return f;
}

// A σ key of the other DR kind would be silently ignored: an error, like an unknown key.
void check_dr_sigmas(const NavConfig& c, const NavDrFile& dr) {
  const auto not_for_this_dr = [&](const char* key, const std::string& what) {
    const auto it = c.lines.find(key);
    throw InputError(fmt::format("{} does not apply here: {}", key, what),
                     {c.file, it == c.lines.end() ? std::optional<int>() : it->second, key});
  };
  if (dr.speed_heading && c.sigma_velocity_m_s)
    not_for_this_dr("sigma_velocity_m_s",
                    fmt::format("{} gives speed and heading{} (set sigma_speed_m_s and sigma_heading_deg); "
                                "sigma_velocity_m_s is for a DR file of v_north_m_s, v_east_m_s",
                                dr.source, c.nmea ? " (NMEA VTG/VBW with HDT)" : ""));
  if (!dr.speed_heading && (c.sigma_speed_m_s || c.sigma_heading_rad))
    not_for_this_dr(c.sigma_speed_m_s ? "sigma_speed_m_s" : "sigma_heading_deg",
                    fmt::format("{} gives velocity components v_north_m_s, v_east_m_s (set sigma_velocity_m_s); "
                                "sigma_speed_m_s and sigma_heading_deg are for a DR file of speed_m_s, "
                                "heading_deg",
                                dr.source));
}

std::string known_names(const std::map<std::string, std::size_t>& m) {
  std::string s;
  for (const auto& [name, i] : m) s += (s.empty() ? "" : ", ") + name;
  return s.empty() ? std::string("none") : s;
}

// LOPs with their station and chain names resolved to indices.
std::vector<nav::LopRecord> resolve_lops(const NavConfig& c, const NavStationsFile& stations, const NavLopsFile& lops) {
  std::map<std::string, std::size_t> station_index, chain_index;
  for (std::size_t k = 0; k < stations.names.size(); ++k) station_index[stations.names[k]] = k;
  for (std::size_t k = 0; k < c.chains.size(); ++k) chain_index[c.chains[k].chain.name] = k;
  std::vector<nav::LopRecord> out;
  for (std::size_t k = 0; k < lops.records.size(); ++k) {
    const NavLopsFile::Record& r = lops.records[k];
    const int line = lops.lines[k];
    const auto station = [&](const std::string& name, const char* column) {
      const auto it = station_index.find(name);
      if (it == station_index.end())
        throw InputError(
            fmt::format("unknown station \"{}\" ({} has {})", name, c.stations_path, known_names(station_index)),
            {lops.source, line, column});
      return it->second;
    };
    nav::LopRecord l;
    l.time_s = r.time_s;
    l.kind = r.kind;
    l.station = station(r.station, "station");
    if (r.kind != NavLopKind::Range) l.station2 = station(r.station2, "station2");
    if (!r.chain.empty()) {
      const auto it = chain_index.find(r.chain);
      if (it == chain_index.end())
        throw InputError(
            fmt::format("chain \"{}\" is not in the configuration's chains: ({})", r.chain, known_names(chain_index)),
            {lops.source, line, "chain"});
      l.chain = it->second;
    }
    (r.kind == NavLopKind::TimeDifference ? l.time_difference_us : l.value_m) = r.value;
    l.sigma_m = r.sigma_m;
    l.source = {lops.source, line};
    out.push_back(l);
  }
  return out;
}

// The records of the files as the line's observations (truth in time order).
void observations(const JobFiles& f, nav::SurveyLine& line) {
  line.dr_kind = f.dr.speed_heading ? nav::DrKind::SpeedHeading : nav::DrKind::Velocity;
  for (std::size_t k = 0; k < f.dr.records.size(); ++k) {
    const NavDrFile::Record& r = f.dr.records[k];
    nav::DrRecord d;
    d.time_s = r.time_s;
    (f.dr.speed_heading ? d.speed_m_s : d.v_north_m_s) = r.a;
    (f.dr.speed_heading ? d.heading_rad : d.v_east_m_s) = r.b;
    d.source = {f.dr.source, f.dr.lines[k]};
    line.dr.push_back(d);
  }
  for (std::size_t k = 0; k < f.stations.names.size(); ++k)
    line.stations.push_back({f.stations.names[k], f.stations.positions[k], {f.stations.source, f.stations.lines[k]}});
  for (std::size_t k = 0; k < f.fixes.records.size(); ++k) {
    const NavFixesFile::Record& r = f.fixes.records[k];
    line.fixes.push_back({r.time_s, r.position, r.sigma_north_m, r.sigma_east_m, {f.fixes.source, f.fixes.lines[k]}});
  }
  std::vector<std::size_t> order(f.truth.records.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return f.truth.records[a].time_s < f.truth.records[b].time_s;
  });
  for (std::size_t k : order)
    line.truth.push_back({f.truth.records[k].time_s, f.truth.records[k].position, {f.truth.source, f.truth.lines[k]}});
}

// The CSV column of a field's member as the user wrote it (none for NMEA logs, whose lines are
// sentences).
SourceMap::ColumnOf column_of(const std::string& array, const NavConfig& c, bool velocity_dr) {
  const bool nmea = c.nmea.has_value() && (array == "dr" || array == "fixes" || array == "truth");
  return [array, nmea, velocity_dr](const std::string& member) -> std::string {
    if (nmea) return {};
    if (member == "value_m") return "value";
    if (member == "x_north_m") return "x_m";
    if (member == "y_east_m") return "y_m";
    if (member == "heading_rad") return "heading_deg";
    if (member == "covariance") return array == "fixes" ? "sigma_m" : "";
    if (member == "position") return array == "truth" ? "" : "lat_deg, lon_deg";
    if (member == "v_north_m_s" || member == "v_east_m_s") return velocity_dr ? member : "";
    return member;
  };
}

template <class Record>
std::vector<SourceRow> rows_of(const std::vector<Record>& records) {
  std::vector<SourceRow> rows;
  rows.reserve(records.size());
  for (const Record& r : records) rows.push_back({r.source.file, r.source.line});
  return rows;
}

// Where each field of the line was read: its rows, and the configuration's keys.
SourceMap sources_of(const nav::SurveyLine& line, const NavConfig& c) {
  const bool velocity = line.dr_kind == nav::DrKind::Velocity;
  SourceMap m;
  m.add_document(c.file, c.lines);
  m.add_document("options", c.file, c.lines);
  m.add_rows("dr", rows_of(line.dr), column_of("dr", c, velocity));
  m.add_rows("epoch", rows_of(line.dr), [](const std::string&) { return std::string(); });
  m.add_rows("stations", rows_of(line.stations), column_of("stations", c, velocity));
  m.add_rows("lops", rows_of(line.lops), column_of("lops", c, velocity));
  m.add_rows("fixes", rows_of(line.fixes), column_of("fixes", c, velocity));
  m.add_rows("truth", rows_of(line.truth), column_of("truth", c, velocity));
  return m;
}

}  // namespace navj
}  // namespace

std::vector<std::string> nav_input_files(const NavConfig& c) {
  std::vector<std::string> files = {c.file};
  for (const std::string& f : {c.dr_path, c.stations_path, c.lops_path, c.fixes_path, c.truth_path})
    if (!f.empty()) files.push_back(f);
  if (c.nmea)
    for (const std::string& f : {c.nmea->heading_path, c.nmea->speed_path, c.nmea->positions_path})
      if (!f.empty()) files.push_back(f);
  return files;
}

NavJob read_nav_job(const NavConfig& c) {
  navj::JobFiles files = navj::read_job_files(c);
  navj::check_dr_sigmas(c, files.dr);
  NavJob job;
  nav::SurveyLine& line = job.line;
  navj::observations(files, line);
  line.lops = navj::resolve_lops(c, files.stations, files.lops);
  line.chains = c.chains;
  if (c.projection) line.projection = c.projection->definition;
  line.initial = c.initial;
  line.initial_sigma_m = c.initial_sigma_m;
  line.initial_source = {c.file, 0};
  line.sigma_speed_m_s = c.sigma_speed_m_s;
  line.sigma_heading_rad = c.sigma_heading_rad;
  line.sigma_velocity_m_s = c.sigma_velocity_m_s;
  line.options = c.options;
  line.notes = std::move(files.notes);
  line.warnings = std::move(files.warnings);
  job.sources = navj::sources_of(line, c);
  return job;
}

NavRun run_nav(const NavConfig& config, Progress* progress) {
  NavRun run;
  run.job = read_nav_job(config);
  run.result = located(run.job.sources, [&] { return nav::process(run.job.line, progress); });
  return run;
}

}  // namespace meridian::io
