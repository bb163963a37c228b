// meridian gravity point | points | grid | synth-model | geoid-grid

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "cli_support.hpp"
#include "commands.hpp"
#include "meridian/core/atomic_file.hpp"
#include "meridian/io/gravity_jobs.hpp"
#include "meridian/report/gravity_html.hpp"
#include "meridian/report/gravity_json.hpp"
#include "meridian/report/gravity_text.hpp"
#include "meridian/report/html.hpp"
#include "meridian/report/json_text.hpp"

namespace meridian::cli {
namespace gravity_cmd {
namespace {

// The model's lines on stderr once it is loaded (a CSV or grid file has no room for them):
// all of them, or with `warnings_only` its warnings alone (which are never silenced).
io::ModelLoaded print_model(bool warnings_only) {
  return [warnings_only](const gravity::ModelInfo& info) {
    std::fputs((warnings_only ? report::model_warnings_text(info) : report::model_text(info)).c_str(), stderr);
  };
}

// Text streamed to a file, written atomically (it appears only on commit(), so nothing does
// unless the whole run succeeds; the temporary file is created with the first text), or to
// standard output (empty path or "-").
class StreamedOutput {
 public:
  explicit StreamedOutput(std::string path) : path_(std::move(path)) {}
  io::TextSink sink() {
    return [this](std::string_view text) {
      if (path_.empty() || path_ == "-") {
        write_standard_output(text, false);
        return;
      }
      if (!file_) file_.emplace(path_);
      file_->write(text);
    };
  }
  void commit() {
    if (file_) file_->commit();
    else write_standard_output({});
  }

 private:
  std::string path_;
  std::optional<AtomicFileWriter> file_;
};

struct PointArgs {
  io::PointRequest request;
  bool json = false;
};

int run_point(const PointArgs& a) {
  const gravity::PointResult r = io::run_gravity_point(a.request);
  emit("", a.json ? report::json_text(report::gravity_point_to_json(r)) : report::gravity_point_text(r));
  return kOk;
}

struct PointsArgs {
  io::PointsRequest request;
  std::string output, report;
  bool quiet = false;
};

int run_points(const PointsArgs& a) {
  require_html_reports_for(a.report);
  const std::string& in = a.request.input == "-" ? std::string() : a.request.input;
  check_output_paths({{a.output, "-o", "output"}, {a.report, "--report", "report"}}, {in, a.request.model.model});
  StreamedOutput csv(a.output);
  TerminalProgress progress(a.quiet);
  const gravity::PointsResult r = io::run_gravity_points(a.request, csv.sink(), print_model(a.quiet), &progress);
  progress.finish();
  // The report is made before anything is committed, and written after the CSV.
  const std::string html = a.report.empty() ? std::string() : report::render_html(report::gravity_points_document(r));
  csv.commit();
  if (!a.report.empty()) write_file_atomically(a.report, html);
  return kOk;
}

struct GridArgs {
  io::GridRequest request;
  bool json = false, quiet = false;
};

int run_grid(const GridArgs& a) {
  TerminalProgress progress(a.quiet);
  const gravity::GridRunResult r = io::run_gravity_grid(a.request, print_model(a.quiet || a.json), &progress);
  progress.finish();
  emit("", a.json ? report::json_text(report::gravity_grid_to_json(r)) : report::gravity_grid_text(r));
  return kOk;
}

struct GeoidGridArgs {
  io::GeoidGridRequest request;
  bool json = false;
};

int run_geoid_grid(const GeoidGridArgs& a) {
  const gravity::GridPointResult r = io::run_geoid_grid_point(a.request);
  emit("", a.json ? report::json_text(report::geoid_grid_to_json(r)) : report::geoid_grid_text(r));
  return kOk;
}

int run_synth(const io::SyntheticModelRequest& a) {
  emit("", report::synthetic_model_text(io::write_synthetic_model(a)));
  return kOk;
}

void add_model_options(CLI::App* c, io::ModelRequest& m) {
  c->add_option("--model", m.model,
                "Model file (.gfc, .egm) or name (egm2008, egm96, ...) found in GeographicLib's gravity directories")
      ->required();
  c->add_option("--max-degree", m.max_degree, "Truncate the model to this degree on load (above the file's degree: the file's)")
      ->check(CLI::Range(0, 100000));
  c->add_option("--threads", m.threads, "Threads (0 = all cores)")->capture_default_str();
}

void add_point_command(CLI::App* g, int& exit_code) {
  auto pa = std::make_shared<PointArgs>();
  CLI::App* point = g->add_subcommand("point", "xi, eta (GeographicLib SphericalAnomaly) and geoid height at one point");
  add_model_options(point, pa->request.model);
  point->add_option("LAT", pa->request.lat, "Geodetic latitude (decimal degrees or DMS)")->required();
  point->add_option("LON", pa->request.lon, "Longitude, east positive (decimal degrees or DMS)")->required();
  point->add_option("H", pa->request.h_m, "Ellipsoidal height (m), default 0");
  point->add_flag("--json", pa->json, "Print one JSON object");
  point->callback([pa, &exit_code] { exit_code = guarded([&] { return run_point(*pa); }); });
}

void add_points_command(CLI::App* g, int& exit_code) {
  auto ps = std::make_shared<PointsArgs>();
  CLI::App* points = g->add_subcommand("points", "xi, eta, geoid for lat,lon[,h] CSV rows (stdin to stdout by default)");
  add_model_options(points, ps->request.model);
  points->add_option("--input", ps->request.input, "CSV file of lat,lon[,h] (default stdin)");
  points->add_option("-o,--output", ps->output, "CSV output file, written atomically (default stdout)");
  points->add_option("--track-tolerance-arcsec", ps->request.track_tolerance_arcsec,
                     "Treat the rows as one survey line: evaluate a subset and interpolate, with xi/eta error at most "
                     "this (checked at every interval's midpoint; geoid to 0.1 mm)");
  points->add_option("--report", ps->report,
                     "Also write a self-contained HTML report (statistics, maps of xi, eta, N) to this file");
  points->add_flag("-q,--quiet", ps->quiet, "No progress bar");
  points->callback([ps, &exit_code] { exit_code = guarded([&] { return run_points(*ps); }); });
}

void add_grid_command(CLI::App* g, int& exit_code) {
  auto sg = std::make_shared<GridArgs>();
  io::GridRequest& r = sg->request;
  CLI::App* sgrid = g->add_subcommand(
      "grid", "xi, eta, geoid, gravity anomaly, disturbance vector on a lat/lon grid (NetCDF, GTX for geoid heights, or CSV)");
  add_model_options(sgrid, r.model);
  sgrid->add_option("-R,--region", r.region, "W/E/S/N in degrees (GMT style), or g (0/360/-90/90), d (-180/180/-90/90)")
      ->required();
  sgrid->add_option("-I,--spacing", r.spacing, "Node spacing: 30s, 5m, 0.5d or plain degrees; X/Y for lon/lat")
      ->required();
  sgrid->add_option("--quantities", r.quantities,
                    "Comma-separated: xi, eta (arcsec), geoid (m), anomaly, dg_east, dg_north, dg_up (mGal)")
      ->capture_default_str();
  CLI::Option* height = sgrid->add_option("--height", r.height_m,
                                          "Ellipsoidal height of every node (m); the geoid ignores it")
                            ->capture_default_str();
  sgrid->add_option("--height-grid", r.height_grid,
                    "NetCDF grid FILE.nc[?VAR] of ellipsoidal heights (m) at exactly the grid's nodes (per-node "
                    "heights: every node evaluated as a point; for regional grids)")
      ->excludes(height);
  sgrid->add_flag("-r,--pixel", r.pixel, "Pixel (cell-centre) registration, GMT -r (default: gridline)");
  sgrid->add_option("--path", r.path,
                    "auto (FFT when the longitude spacing divides 360° and the grid is global or wide enough, else per "
                    "parallel) | fft | parallel")->capture_default_str();
  sgrid->add_option("-o,--output", r.output, "Output file, written atomically: .nc (NetCDF), .gtx (geoid heights only, float32) or .csv (small grids)")
      ->required();
  sgrid->add_flag("--json", sg->json, "Print a JSON summary");
  sgrid->add_flag("-q,--quiet", sg->quiet, "No progress bar, no model lines");
  sgrid->callback([sg, &exit_code] { exit_code = guarded([&] { return run_grid(*sg); }); });
}

void add_geoid_grid_command(CLI::App* g, int& exit_code) {
  auto ga = std::make_shared<GeoidGridArgs>();
  CLI::App* grid = g->add_subcommand("geoid-grid", "Geoid height from a .gtx/.pgm grid (DOV from its slope: fallback only)");
  grid->add_option("--grid", ga->request.grid, "Geoid grid file (.gtx, .pgm)")->required();
  grid->add_option("LAT", ga->request.lat, "Geodetic latitude (decimal degrees or DMS)")->required();
  grid->add_option("LON", ga->request.lon, "Longitude, east positive")->required();
  grid->add_option("--interpolation", ga->request.interpolation, "bicubic | bilinear")->capture_default_str();
  grid->add_flag("--json", ga->json, "Print JSON");
  grid->callback([ga, &exit_code] { exit_code = guarded([&] { return run_geoid_grid(*ga); }); });
}

void add_synth_command(CLI::App* g, int& exit_code) {
  auto sa = std::make_shared<io::SyntheticModelRequest>();
  CLI::App* synth = g->add_subcommand("synth-model", "Write a random Kaula-rule model as PREFIX.gfc, PREFIX.egm, PREFIX.egm.cof");
  synth->add_option("--degree", sa->degree, "Maximum degree, 2..2190")->capture_default_str();
  synth->add_option("--seed", sa->seed, "Random seed (same seed, same model)")->capture_default_str();
  synth->add_option("--out", sa->out, "Output prefix")->required();
  synth->callback([sa, &exit_code] { exit_code = guarded([&] { return run_synth(*sa); }); });
}

}  // namespace
}  // namespace gravity_cmd

void add_gravity_commands(CLI::App& app, int& exit_code) {
  CLI::App* g = app.add_subcommand("gravity", "Global gravity field models: deflection of the vertical, geoid");
  g->require_subcommand(1);
  gravity_cmd::add_point_command(g, exit_code);
  gravity_cmd::add_points_command(g, exit_code);
  gravity_cmd::add_grid_command(g, exit_code);
  gravity_cmd::add_geoid_grid_command(g, exit_code);
  gravity_cmd::add_synth_command(g, exit_code);
}

}  // namespace meridian::cli
