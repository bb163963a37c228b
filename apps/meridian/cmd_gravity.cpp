// meridian gravity point | points | synth-model

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "commands.hpp"
#include "meridian/core/atomic_file.hpp"
#include "meridian/core/dms.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gravity/egm_format.hpp"
#include "meridian/gravity/geoid_grid.hpp"
#include "meridian/gravity/gravity_field.hpp"
#include "meridian/gravity/icgem.hpp"
#include "meridian/gravity/model_lookup.hpp"
#include "meridian/gravity/synthetic.hpp"
#include "meridian/gravity/track.hpp"

namespace meridian::cli {
namespace {

struct ModelArgs {
  std::string model;
  int max_degree = -1;
  unsigned threads = 0;
};

struct PointArgs : ModelArgs {
  std::string lat, lon;
  double h = 0;
  bool json = false;
};

struct PointsArgs : ModelArgs {
  std::string input, output;
  double track_tolerance_arcsec = 0;  // > 0: rows are one track, interpolated
  bool quiet = false;
};

struct GridArgs {
  std::string grid, lat, lon, interpolation = "bicubic";
  bool json = false;
};

struct SynthArgs {
  int degree = 360;
  std::uint64_t seed = 1;
  std::string out;
};

gravity::GravityModelData load(const ModelArgs& a) {
  return gravity::load_model(a.model, {a.max_degree, -1});
}

double parse_coordinate(const std::string& text, const char* what, double limit_deg) {
  Angle a = Angle::radians(0);
  try {
    a = parse_angle(text);
  } catch (Error& e) {
    e.add_context("", std::nullopt, what);
    throw;
  }
  if (std::abs(a.deg()) > limit_deg)
    throw InputError(fmt::format("{} {} deg is outside [-{}, {}]", what, a.deg(), limit_deg, limit_deg), {"", {}, what});
  return a.rad();
}

int run_point(const PointArgs& a) {
  const gravity::GravityModelData m = load(a);
  const gravity::GravityField field(m, {false, a.threads});
  const gravity::GeodeticPoint p{parse_coordinate(a.lat, "latitude", 90), parse_coordinate(a.lon, "longitude", 540), a.h};
  const gravity::FieldValues v = field.evaluate(p);
  const double xi = units::rad_to_arcsec(v.xi_rad), eta = units::rad_to_arcsec(v.eta_rad);
  std::string out;
  if (a.json) {
    const nlohmann::json j = {{"model", m.name},
                              {"model_file", m.source_file},
                              {"max_degree", field.max_degree()},
                              {"latitude_deg", units::rad_to_deg(p.lat_rad)},
                              {"longitude_deg", units::rad_to_deg(p.lon_rad)},
                              {"height_m", p.height_m},
                              {"xi_arcsec", xi},
                              {"eta_arcsec", eta},
                              {"geoid_m", v.geoid_m},
                              {"gravity_anomaly_mgal", v.anomaly_m_s2 * 1e5},
                              {"xi_astro_arcsec", units::rad_to_arcsec(v.xi_astro_rad)},
                              {"eta_astro_arcsec", units::rad_to_arcsec(v.eta_astro_rad)},
                              {"disturbing_potential_m2_s2", v.disturbing_potential_m2_s2}};
    out = j.dump(2) + "\n";
  } else {
    out = fmt::format(
        "model {} (degree {}, {})\npoint lat {:.9f} deg, lon {:.9f} deg, h {:.3f} m\n"
        "xi_arcsec  {:.9f}\neta_arcsec {:.9f}\ngeoid_m    {:.9f}\n",
        m.name, field.max_degree(), m.source_file, units::rad_to_deg(p.lat_rad), units::rad_to_deg(p.lon_rad), p.height_m,
        xi, eta, v.geoid_m);
  }
  emit("", out);
  return kOk;
}

// Reads lat,lon[,h] rows a chunk at a time, so a survey line of millions of
// samples never sits in memory: '#' comments, blank lines and one
// non-numeric header line are skipped.
class PointReader {
 public:
  PointReader(std::istream& in, std::string name) : in_(in), name_(std::move(name)) {}

  /// Append up to `max` points to `out` (cleared first); false at the end.
  bool next(std::vector<gravity::GeodeticPoint>& out, std::size_t max) {
    out.clear();
    std::string line;
    while (out.size() < max && std::getline(in_, line)) {
      ++line_no_;
      bytes_ += line.size() + 1;
      if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      std::vector<std::string> f;
      std::stringstream ss(line);
      for (std::string cell; std::getline(ss, cell, ',');) {
        const auto b = cell.find_first_not_of(" \t\r"), e = cell.find_last_not_of(" \t\r");
        f.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
      }
      const bool first = !seen_data_;
      seen_data_ = true;
      if (first && !f.empty() && !f[0].empty() && std::isalpha(static_cast<unsigned char>(f[0][0]))) continue;
      try {
        out.push_back(parse(f));
      } catch (Error& e) {
        e.add_context(name_, line_no_);
        throw;
      }
    }
    return !out.empty();
  }
  std::size_t bytes_read() const { return bytes_; }

 private:
  static gravity::GeodeticPoint parse(const std::vector<std::string>& f) {
    if (f.size() < 2 || f.size() > 3)
      throw InputError(fmt::format("expected lat,lon[,h] (2 or 3 fields), got {}", f.size()));
    gravity::GeodeticPoint p{parse_coordinate(f[0], "latitude", 90), parse_coordinate(f[1], "longitude", 540), 0.0};
    if (f.size() == 3) {
      std::size_t used = 0;
      try {
        p.height_m = std::stod(f[2], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != f[2].size() || f[2].empty()) throw ParseError("height \"" + f[2] + "\" is not a number", {"", {}, "h"});
    }
    gravity::GravityField::check_point(p);
    return p;
  }
  std::istream& in_;
  std::string name_;
  int line_no_ = 0;
  std::size_t bytes_ = 0;
  bool seen_data_ = false;
};

int run_points(const PointsArgs& a) {
  std::ifstream file;
  std::istream* in = &std::cin;
  std::string name = "<stdin>";
  std::size_t total_bytes = 0;  // unknown for stdin
  if (!a.input.empty() && a.input != "-") {
    file.open(a.input);
    if (!file) throw IoError("cannot open input file", {a.input, {}, ""});
    in = &file;
    name = a.input;
    std::error_code ec;
    total_bytes = static_cast<std::size_t>(std::filesystem::file_size(a.input, ec));
  }
  const gravity::GravityModelData m = load(a);
  const gravity::GravityField field(m, {false, a.threads});
  // With a file output nothing appears unless the whole run succeeds.
  std::unique_ptr<AtomicFileWriter> writer;
  if (!a.output.empty() && a.output != "-") writer = std::make_unique<AtomicFileWriter>(a.output);
  auto put = [&](const std::string& text) {
    if (writer) writer->write(text);
    else std::fwrite(text.data(), 1, text.size(), stdout);
  };
  put("lat_deg,lon_deg,h_m,xi_arcsec,eta_arcsec,geoid_m\n");
  TerminalProgress progress(a.quiet);
  PointReader reader(*in, name);
  // Track interpolation works on a stretch of line at a time; chunks are
  // long enough that their ends cost little.
  const std::size_t chunk = a.track_tolerance_arcsec > 0 ? 200000 : 16384;
  std::vector<gravity::GeodeticPoint> pts;
  std::size_t done = 0;
  while (reader.next(pts, chunk)) {
    std::vector<gravity::FieldValues> v;
    if (a.track_tolerance_arcsec > 0) {
      gravity::TrackOptions to;
      to.tolerance_rad = units::arcsec_to_rad(a.track_tolerance_arcsec);
      to.tolerance_geoid_m = 1e-4;
      v = gravity::evaluate_track(field, pts, gravity::Quantities::All, to).values;
    } else {
      v = field.evaluate(pts);
    }
    fmt::memory_buffer b;
    for (std::size_t i = 0; i < pts.size(); ++i)
      fmt::format_to(std::back_inserter(b), "{:.10f},{:.10f},{:.4f},{:.9f},{:.9f},{:.9f}\n",
                     units::rad_to_deg(pts[i].lat_rad), units::rad_to_deg(pts[i].lon_rad), pts[i].height_m,
                     units::rad_to_arcsec(v[i].xi_rad), units::rad_to_arcsec(v[i].eta_rad), v[i].geoid_m);
    put(fmt::to_string(b));
    done += pts.size();
    if (total_bytes > 0) progress.update(reader.bytes_read(), total_bytes, "points (bytes of input)");
    else progress.update(done, 0, "points");
  }
  progress.finish();
  if (writer) writer->commit();
  else std::fflush(stdout);
  return kOk;
}

int run_synth(const SynthArgs& a) {
  if (a.out.empty()) throw InputError("--out PREFIX is required", {"", {}, "--out"});
  const gravity::GravityModelData m = gravity::make_synthetic_model({a.degree, a.seed, 1e-5});
  const std::string gfc = gravity::format_icgem(m);
  write_file_atomically(a.out + ".gfc", gfc);
  gravity::write_egm_files(m, a.out);
  emit("", fmt::format("wrote {0}.gfc, {0}.egm, {0}.egm.cof (model {1}, degree {2}, seed {3})\n", a.out, m.name,
                       a.degree, a.seed));
  return kOk;
}

int run_grid(const GridArgs& a) {
  const gravity::GeoidGrid g = gravity::read_geoid_grid(a.grid);
  const double lat = parse_coordinate(a.lat, "latitude", 90), lon = parse_coordinate(a.lon, "longitude", 540);
  gravity::GridInterpolation interp;
  if (a.interpolation == "bicubic") interp = gravity::GridInterpolation::Bicubic;
  else if (a.interpolation == "bilinear") interp = gravity::GridInterpolation::Bilinear;
  else throw InputError("unknown interpolation \"" + a.interpolation + "\" (bilinear or bicubic)", {"", {}, "--interpolation"});
  const double n = gravity::grid_geoid_height_m(g, lat, lon, interp);
  const gravity::GridDeflection d = gravity::grid_deflection_fallback(g, lat, lon);
  std::string out;
  if (a.json) {
    const nlohmann::json j = {{"grid", g.source_file}, {"interpolation", a.interpolation},
                              {"latitude_deg", units::rad_to_deg(lat)}, {"longitude_deg", units::rad_to_deg(lon)},
                              {"geoid_m", n}, {"fallback_xi_arcsec", units::rad_to_arcsec(d.xi_rad)},
                              {"fallback_eta_arcsec", units::rad_to_arcsec(d.eta_rad)}, {"fallback_method", d.method}};
    out = j.dump(2) + "\n";
  } else {
    out = fmt::format("grid {} ({})\ngeoid_m    {:.6f}\nxi_arcsec  {:.3f}  [{}]\neta_arcsec {:.3f}  [{}]\n", g.source_file,
                      a.interpolation, n, units::rad_to_arcsec(d.xi_rad), d.method, units::rad_to_arcsec(d.eta_rad), d.method);
  }
  emit("", out);
  return kOk;
}

void add_model_options(CLI::App* c, ModelArgs& a) {
  c->add_option("--model", a.model,
                "Model file (.gfc, .egm) or name (egm2008, egm96, ...) found in GeographicLib's gravity directories")
      ->required();
  c->add_option("--max-degree", a.max_degree, "Truncate the model to this degree on load");
  c->add_option("--threads", a.threads, "Threads (0 = all cores)")->capture_default_str();
}

}  // namespace

void add_gravity_commands(CLI::App& app, int& exit_code) {
  CLI::App* g = app.add_subcommand("gravity", "Global gravity field models: deflection of the vertical, geoid");
  g->require_subcommand(1);

  auto pa = std::make_shared<PointArgs>();
  CLI::App* point = g->add_subcommand("point", "xi, eta (GeographicLib SphericalAnomaly) and geoid height at one point");
  add_model_options(point, *pa);
  point->add_option("LAT", pa->lat, "Geodetic latitude (decimal degrees or DMS)")->required();
  point->add_option("LON", pa->lon, "Longitude, east positive (decimal degrees or DMS)")->required();
  point->add_option("H", pa->h, "Ellipsoidal height (m), default 0");
  point->add_flag("--json", pa->json, "Print one JSON object");
  point->callback([pa, &exit_code] { exit_code = guarded([&] { return run_point(*pa); }); });

  auto ps = std::make_shared<PointsArgs>();
  CLI::App* points = g->add_subcommand("points", "xi, eta, geoid for lat,lon[,h] CSV rows (stdin to stdout by default)");
  add_model_options(points, *ps);
  points->add_option("--input", ps->input, "CSV file of lat,lon[,h] (default stdin)");
  points->add_option("-o,--output", ps->output, "CSV output file, written atomically (default stdout)");
  points->add_option("--track-tolerance-arcsec", ps->track_tolerance_arcsec,
                     "Treat the rows as one survey line: evaluate a subset and interpolate, with xi/eta error at most "
                     "this (checked at every interval's midpoint; geoid to 0.1 mm)");
  points->add_flag("-q,--quiet", ps->quiet, "No progress bar");
  points->callback([ps, &exit_code] { exit_code = guarded([&] { return run_points(*ps); }); });

  auto ga = std::make_shared<GridArgs>();
  CLI::App* grid = g->add_subcommand("geoid-grid", "Geoid height from a .gtx/.pgm grid (DOV from its slope: fallback only)");
  grid->add_option("--grid", ga->grid, "Geoid grid file (.gtx, .pgm)")->required();
  grid->add_option("LAT", ga->lat, "Geodetic latitude (decimal degrees or DMS)")->required();
  grid->add_option("LON", ga->lon, "Longitude, east positive")->required();
  grid->add_option("--interpolation", ga->interpolation, "bicubic | bilinear")->capture_default_str();
  grid->add_flag("--json", ga->json, "Print JSON");
  grid->callback([ga, &exit_code] { exit_code = guarded([&] { return run_grid(*ga); }); });

  auto sa = std::make_shared<SynthArgs>();
  CLI::App* synth = g->add_subcommand("synth-model", "Write a random Kaula-rule model as PREFIX.gfc, PREFIX.egm, PREFIX.egm.cof");
  synth->add_option("--degree", sa->degree, "Maximum degree, 2..2190")->capture_default_str();
  synth->add_option("--seed", sa->seed, "Random seed (same seed, same model)")->capture_default_str();
  synth->add_option("--out", sa->out, "Output prefix")->required();
  synth->callback([sa, &exit_code] { exit_code = guarded([&] { return run_synth(*sa); }); });
}

}  // namespace meridian::cli
