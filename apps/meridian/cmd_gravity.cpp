// meridian gravity point | points | grid | synth-model | geoid-grid

#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "cli_support.hpp"
#include "commands.hpp"
#include "meridian/core/atomic_file.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gravity/egm_format.hpp"
#include "meridian/gravity/geoid_grid.hpp"
#include "meridian/gravity/gravity_field.hpp"
#include "meridian/gravity/grid_spec.hpp"
#include "meridian/gravity/grid_synthesis.hpp"
#include "meridian/gravity/icgem.hpp"
#include "meridian/gravity/model_lookup.hpp"
#include "meridian/gravity/points.hpp"
#include "meridian/gravity/synthetic.hpp"
#include "meridian/io/gravity_grid_files.hpp"
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

struct SynthGridArgs : ModelArgs {
  std::string region, spacing, quantities = "xi,eta,geoid", output, path = "auto", height_grid;
  double height_m = 0;
  bool pixel = false, json = false, quiet = false;
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
  gravity::GravityModelData m = load(a);  // its coefficients move into the field (no 38 MB copy)
  const gravity::GravityField field(std::move(m), {false, a.threads});
  const gravity::GeodeticPoint p{io::parse_latitude_rad(a.lat), io::parse_longitude_rad(a.lon), a.h};
  const gravity::PointResult r{gravity::model_info(m, field), p, field.evaluate(p)};
  emit("", a.json ? json_text(report::gravity_point_to_json(r)) : report::gravity_point_text(r));
  return kOk;
}

int run_points(const PointsArgs& a) {
  require_html_reports_for(a.report);
  io::PointsInput input(a.input);
  gravity::GravityModelData m = load(a);  // its coefficients move into the field (no 38 MB copy)
  const gravity::GravityField field(std::move(m), {false, a.threads});
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

// `gravity grid`: every check (region, spacing, quantities, output path) before the model is
// loaded; the file is opened (created as a temporary) before synthesis and renamed at the end.
int run_synth_grid(const SynthGridArgs& a) {
  gravity::GridSpec spec;
  gravity::parse_grid_region(a.region, spec);
  gravity::parse_grid_spacing(a.spacing, spec.lon_spacing_deg, spec.lat_spacing_deg);
  spec.registration = a.pixel ? gravity::GridRegistration::Pixel : gravity::GridRegistration::Gridline;
  spec.height_m = a.height_m;
  for (std::size_t start = 0; start <= a.quantities.size();) {
    const std::size_t comma = std::min(a.quantities.find(',', start), a.quantities.size());
    const std::string name = a.quantities.substr(start, comma - start);
    if (!name.empty()) spec.quantities.push_back(gravity::grid_quantity_from_string(name));
    start = comma + 1;
  }
  gravity::GridOptions options;
  options.path = gravity::grid_path_from_string(a.path);
  options.threads = a.threads;
  if (a.output.empty()) throw InputError("-o/--output FILE (.nc or .csv) is required", {"", {}, "--output"});
  spec.validate();
  // Per-node heights: the file is opened and checked against the nodes before any work.
  std::unique_ptr<io::GridHeightFile> heights;
  if (!a.height_grid.empty()) {
    heights = std::make_unique<io::GridHeightFile>(a.height_grid, spec);
    spec.node_heights = heights->source();
  }
  gravity::choose_grid_path(spec, options);  // every check that does not need the model
  io::check_grid_output(a.output, spec);

  gravity::GravityModelData m = load(a);  // its coefficients move into the field (no 38 MB copy)
  const gravity::GravityField field(std::move(m), {false, a.threads});
  const gravity::ModelInfo info = gravity::model_info(m, field);
  if (!a.quiet && !a.json) std::fputs(report::model_text(info).c_str(), stderr);
  else
    for (const std::string& w : gravity::model_warnings(info)) std::fprintf(stderr, "warning: %s\n", w.c_str());
  const gravity::GridPath path = gravity::choose_grid_path(spec, options, field.max_order());
  io::GridFileMetadata meta;
  meta.model_name = m.name;
  meta.model_file = m.source_file;
  meta.max_degree = field.max_degree();
  meta.tide_system = m.tide_system;
  meta.path = path;
  const std::string height_arg =
      heights ? "--height-grid " + a.height_grid : fmt::format("--height {}", a.height_m);
  meta.history = fmt::format("meridian gravity grid --model {} --region {} --spacing {} --quantities {} {}{} "
                             "--path {} -o {}",
                             a.model, a.region, a.spacing, a.quantities, height_arg, a.pixel ? " -r" : "", a.path,
                             a.output);
  if (heights) meta.height_source = a.height_grid;
  const std::unique_ptr<io::GridFileWriter> writer = io::open_grid_file(a.output, spec, meta);
  TerminalProgress progress(a.quiet);
  const auto start = std::chrono::steady_clock::now();
  const gravity::GridSynthesisResult r = gravity::synthesize_grid(
      field, spec, [&](const gravity::GridRow& row) { writer->write_row(row); }, &progress, options);
  progress.finish();
  writer->commit();
  const double elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const io::GridFileFormat format = io::grid_file_format_for(a.output);
  const char* format_name = format == io::GridFileFormat::NetCdf ? "NetCDF"
                            : format == io::GridFileFormat::Gtx  ? "GTX"
                                                                 : "CSV";
  if (a.json) {
    nlohmann::json q = nlohmann::json::array();
    for (gravity::GridQuantity x : spec.quantities) {
      const io::GridQuantityFormat f = io::grid_quantity_format(x);
      q.push_back({{"name", std::string(f.name)}, {"units", std::string(f.units)}, {"long_name", std::string(f.long_name)}});
    }
    const nlohmann::json j = {{"output", a.output},
                              {"format", std::string(io::to_string(format))},
                              {"model", m.name},
                              {"model_file", m.source_file},
                              {"max_degree", field.max_degree()},
                              {"region_deg", {spec.west_deg, spec.east_deg, spec.south_deg, spec.north_deg}},
                              {"lon_spacing_deg", spec.lon_spacing_deg},
                              {"lat_spacing_deg", spec.lat_spacing_deg},
                              {"registration", std::string(gravity::to_string(spec.registration))},
                              {"height_m", heights ? nlohmann::json(nullptr) : nlohmann::json(spec.height_m)},
                              {"height_grid", heights ? nlohmann::json(a.height_grid) : nlohmann::json(nullptr)},
                              {"rows", r.rows},
                              {"columns", r.columns},
                              {"nodes", spec.nodes()},
                              {"quantities", q},
                              {"path_used", std::string(gravity::to_string(r.path_used))},
                              {"fft_length", r.fft_length},
                              {"threads", r.threads},
                              {"elapsed_s", elapsed_s}};
    emit("", json_text(j));
  } else {
    std::string names;
    for (gravity::GridQuantity x : spec.quantities) {
      const io::GridQuantityFormat f = io::grid_quantity_format(x);
      names += fmt::format("{}{} [{}]", names.empty() ? "" : ", ", f.name, f.units);
    }
    emit("", fmt::format("wrote {} ({}): {} x {} nodes (lon x lat, {} registration), {}\n"
                         "heights {}\npath {}{}, {}, {:.2f} s\n",
                         a.output, format_name, r.columns, r.rows, gravity::to_string(spec.registration),
                         names,
                         heights ? "per node from " + a.height_grid : fmt::format("{} m at every node", spec.height_m),
                         gravity::to_string(r.path_used),
                         r.fft_length ? fmt::format(" (one real FFT of length {} per parallel and quantity)", r.fft_length)
                         : r.per_node_heights ? std::string(" (every node as a scattered point: per-node heights)")
                                              : std::string(" (GravityCircle per parallel)"),
                         r.per_node_heights ? std::string("parallels in order, each one's nodes over the threads")
                                            : fmt::format("{} thread(s) over parallels", r.threads),
                         elapsed_s));
  }
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
  c->add_option("--max-degree", a.max_degree, "Truncate the model to this degree on load (above the file's degree: the file's)")
      ->check(CLI::Range(0, 100000));
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

  auto sg = std::make_shared<SynthGridArgs>();
  CLI::App* sgrid = g->add_subcommand(
      "grid", "xi, eta, geoid, gravity anomaly, disturbance vector on a lat/lon grid (NetCDF, GTX for geoid heights, or CSV)");
  add_model_options(sgrid, *sg);
  sgrid->add_option("-R,--region", sg->region, "W/E/S/N in degrees (GMT style), or g (0/360/-90/90), d (-180/180/-90/90)")
      ->required();
  sgrid->add_option("-I,--spacing", sg->spacing, "Node spacing: 30s, 5m, 0.5d or plain degrees; X/Y for lon/lat")
      ->required();
  sgrid->add_option("--quantities", sg->quantities,
                    "Comma-separated: xi, eta (arcsec), geoid (m), anomaly, dg_east, dg_north, dg_up (mGal)")
      ->capture_default_str();
  CLI::Option* height = sgrid->add_option("--height", sg->height_m,
                                          "Ellipsoidal height of every node (m); the geoid ignores it")
                            ->capture_default_str();
  sgrid->add_option("--height-grid", sg->height_grid,
                    "NetCDF grid FILE.nc[?VAR] of ellipsoidal heights (m) at exactly the grid's nodes (per-node "
                    "heights: every node evaluated as a point; for regional grids)")
      ->excludes(height);
  sgrid->add_flag("-r,--pixel", sg->pixel, "Pixel (cell-centre) registration, GMT -r (default: gridline)");
  sgrid->add_option("--path", sg->path,
                    "auto (FFT when the longitude spacing divides 360° and the grid is global or wide enough, else per "
                    "parallel) | fft | parallel")->capture_default_str();
  sgrid->add_option("-o,--output", sg->output, "Output file, written atomically: .nc (NetCDF), .gtx (geoid heights only, float32) or .csv (small grids)")
      ->required();
  sgrid->add_flag("--json", sg->json, "Print a JSON summary");
  sgrid->add_flag("-q,--quiet", sg->quiet, "No progress bar, no model lines");
  sgrid->callback([sg, &exit_code] { exit_code = guarded([&] { return run_synth_grid(*sg); }); });

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
