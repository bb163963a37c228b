// meridian gravity point | points | synth-model | geoid-grid

#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "cli_support.hpp"
#include "commands.hpp"
#include "meridian/core/atomic_file.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gravity/egm_format.hpp"
#include "meridian/gravity/geoid_grid.hpp"
#include "meridian/gravity/gravity_field.hpp"
#include "meridian/gravity/icgem.hpp"
#include "meridian/gravity/model_lookup.hpp"
#include "meridian/gravity/points.hpp"
#include "meridian/gravity/synthetic.hpp"
#include "meridian/io/gravity_jobs.hpp"
#include "meridian/io/gravity_points.hpp"
#include "meridian/report/gravity_html.hpp"
#include "meridian/report/gravity_json.hpp"
#include "meridian/report/gravity_text.hpp"
#include "meridian/report/html.hpp"

namespace meridian::cli {
namespace gravity_cmd {
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
  std::string input, output, report;
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

// Text read from files is validated as UTF-8 by the readers; a path is
// whatever the file system holds, so bytes that are not UTF-8 become U+FFFD.
std::string json_text(const nlohmann::json& j) {
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

gravity::GravityModelData load(const ModelArgs& a) {
  return gravity::load_model(a.model, {a.max_degree, -1});
}

int run_point(const PointArgs& a) {
  const gravity::GravityModelData m = load(a);
  const gravity::GravityField field(m, {false, a.threads});
  const gravity::GeodeticPoint p{io::parse_latitude_rad(a.lat), io::parse_longitude_rad(a.lon), a.h};
  const gravity::PointResult r{gravity::model_info(m, field), p, field.evaluate(p)};
  emit("", a.json ? json_text(report::gravity_point_to_json(r)) : report::gravity_point_text(r));
  return kOk;
}

int run_points(const PointsArgs& a) {
  require_html_reports_for(a.report);
  io::PointsInput input(a.input);
  const gravity::GravityModelData m = load(a);
  const gravity::GravityField field(m, {false, a.threads});
  // The CSV has no room for it: the model as its file states it goes to
  // stderr (and the report); warnings even with --quiet.
  {
    const gravity::ModelInfo info = gravity::model_info(m, field);
    if (!a.quiet) std::fputs(report::model_text(info).c_str(), stderr);
    else
      for (const std::string& w : gravity::model_warnings(info)) std::fprintf(stderr, "warning: %s\n", w.c_str());
  }
  gravity::PointsOptions options;
  if (a.track_tolerance_arcsec > 0) options.track_tolerance_rad = units::arcsec_to_rad(a.track_tolerance_arcsec);
  // With a file output nothing appears unless the whole run succeeds.
  std::optional<AtomicFileWriter> csv;
  if (!a.output.empty() && a.output != "-") csv.emplace(a.output);
  const io::TextSink write = [&](std::string_view text) {
    if (csv) csv->write(text);
    else std::fwrite(text.data(), 1, text.size(), stdout);
  };
  TerminalProgress progress(a.quiet);
  const gravity::PointsSummary summary = io::run_gravity_points(input, field, options, write, &progress);
  progress.finish();
  // The report is made before anything is committed, and written after the CSV.
  const std::string html =
      a.report.empty() ? std::string()
                       : report::render_html(report::gravity_points_document(input.name(), gravity::model_info(m, field),
                                                                             options, summary));
  if (csv) csv->commit();
  else std::fflush(stdout);
  if (!a.report.empty()) write_file_atomically(a.report, html);
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
  const double lat = io::parse_latitude_rad(a.lat), lon = io::parse_longitude_rad(a.lon);
  gravity::GridInterpolation interp;
  if (a.interpolation == "bicubic") interp = gravity::GridInterpolation::Bicubic;
  else if (a.interpolation == "bilinear") interp = gravity::GridInterpolation::Bilinear;
  else throw InputError("unknown interpolation \"" + a.interpolation + "\" (bilinear or bicubic)", {"", {}, "--interpolation"});
  const gravity::GridPointResult r = gravity::evaluate_grid_point(g, lat, lon, interp);
  emit("", a.json ? json_text(report::geoid_grid_to_json(r)) : report::geoid_grid_text(r));
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
}  // namespace gravity_cmd

void add_gravity_commands(CLI::App& app, int& exit_code) {
  using namespace gravity_cmd;  // the command's option structs and run functions
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
  points->add_option("--report", ps->report,
                     "Also write a self-contained HTML report (statistics, maps of xi, eta, N) to this file");
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
