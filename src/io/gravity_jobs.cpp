#include "meridian/io/gravity_jobs.hpp"

#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "meridian/core/atomic_file.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gravity/grid_synthesis.hpp"
#include "meridian/io/gravity_csv.hpp"
#include "meridian/io/gravity_egm.hpp"
#include "meridian/io/gravity_geoid_grid.hpp"
#include "meridian/io/gravity_grid_files.hpp"
#include "meridian/io/gravity_icgem.hpp"
#include "meridian/io/gravity_model_lookup.hpp"
#include "meridian/io/gravity_points.hpp"

namespace meridian::io {
namespace {

// The rows of a PointsInput as the points of gravity::process_points.
class PointsFileSource final : public gravity::PointSource {
 public:
  explicit PointsFileSource(PointsInput& input) : input_(input), reader_(input.stream(), input.name()) {}
  bool next(std::vector<gravity::GeodeticPoint>& out, std::size_t max) override { return reader_.next(out, max); }
  std::string name() const override { return input_.name(); }
  std::uint64_t bytes_read() const override { return reader_.bytes_read(); }
  std::uint64_t size_bytes() const override { return input_.size_bytes(); }

 private:
  PointsInput& input_;
  GravityPointReader reader_;
};

// The grid a request names, checked (GridSpec::validate), without per-node heights.
gravity::GridSpec grid_spec(const GridRequest& a) {
  gravity::GridSpec spec;
  gravity::parse_grid_region(a.region, spec);
  gravity::parse_grid_spacing(a.spacing, spec.lon_spacing_deg, spec.lat_spacing_deg);
  spec.registration = a.pixel ? gravity::GridRegistration::Pixel : gravity::GridRegistration::Gridline;
  spec.height_m = a.height_m;
  spec.quantities = gravity::parse_grid_quantities(a.quantities);
  return spec;
}

// The NetCDF attributes that say where a grid's numbers come from; `history` is the command
// line the request stands for.
GridFileMetadata grid_metadata(const GridRequest& a, const gravity::ModelInfo& model, const gravity::NormalGravity& normal,
                               gravity::GridPath path) {
  GridFileMetadata meta;
  meta.model_name = model.name;
  meta.model_file = model.source_file;
  meta.max_degree = model.max_degree;
  meta.tide_system = model.tide_system;
  meta.path = path;
  const std::string height_arg =
      a.height_grid.empty() ? fmt::format("--height {}", a.height_m) : "--height-grid " + a.height_grid;
  meta.history = fmt::format("meridian gravity grid --model {} --region {} --spacing {} --quantities {} {}{} "
                             "--path {} -o {}",
                             a.model.model, a.region, a.spacing, a.quantities, height_arg, a.pixel ? " -r" : "",
                             a.path, a.output);
  meta.height_source = a.height_grid;
  meta.ellipsoid_a_m = normal.a_m();
  meta.ellipsoid_flattening = normal.flattening();
  return meta;
}

// What the summary of a grid run shows besides the synthesis.
gravity::GridRunResult grid_result(const GridRequest& a, const gravity::GridSpec& spec, const gravity::ModelInfo& model) {
  gravity::GridRunResult r;
  r.output = a.output;
  const GridFileFormat format = grid_file_format_for(a.output);
  r.format = std::string(to_string(format));
  r.format_label = std::string(display_name(format));
  r.stored_columns = stored_grid_columns(a.output, spec);
  r.model = model;
  r.spec = spec;
  r.spec.node_heights = nullptr;  // the height file closes with the run
  r.height_grid = a.height_grid;
  for (gravity::GridQuantity q : spec.quantities) {
    const GridQuantityFormat f = grid_quantity_format(q);
    r.quantities.push_back({std::string(f.name), std::string(f.units), std::string(f.long_name)});
  }
  return r;
}

gravity::GridInterpolation interpolation_from_string(const std::string& name) {
  if (name == "bicubic") return gravity::GridInterpolation::Bicubic;
  if (name == "bilinear") return gravity::GridInterpolation::Bilinear;
  throw InputError("unknown interpolation \"" + name + "\" (bilinear or bicubic)", {"", {}, "--interpolation"});
}

}  // namespace

LoadedModel prepare_model(gravity::GravityModelData&& data, unsigned threads) {
  gravity::GravityField field(std::move(data), {false, threads});  // takes the coefficients over
  gravity::ModelInfo info = gravity::model_info(data, field);       // data keeps its metadata
  return {std::move(info), std::move(field)};
}

LoadedModel load_gravity_field(const ModelRequest& request) {
  return prepare_model(load_model(request.model, {request.max_degree, -1}), request.threads);
}

gravity::PointResult run_gravity_point(const PointRequest& request) {
  const LoadedModel m = load_gravity_field(request.model);
  const gravity::GeodeticPoint p{parse_latitude_rad(request.lat), parse_longitude_rad(request.lon), request.h_m};
  return {m.info, p, m.field.evaluate(p)};
}

PointsInput::PointsInput(const std::string& path) : in_(&std::cin), name_("<stdin>") {
  if (path.empty() || path == "-") return;
  file_.open(path);
  if (!file_) throw IoError("cannot open input file", {path, {}, ""});
  in_ = &file_;
  name_ = path;
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec) size_ = size;
}

gravity::PointsResult run_gravity_points(PointsInput& input, const gravity::GravityField& field,
                                         const gravity::ModelInfo& model, const gravity::PointsOptions& options,
                                         const TextSink& write, Progress* progress, std::size_t sample_capacity) {
  write(gravity_points_csv_header());
  PointsFileSource source(input);
  std::string text;
  const gravity::PointSink csv = [&](std::span<const gravity::GeodeticPoint> points,
                                     std::span<const gravity::FieldValues> values) {
    text.clear();
    append_gravity_points_csv(text, points, values);
    write(text);
  };
  return gravity::process_points(source, field, model, options, csv, progress, sample_capacity);
}

gravity::PointsResult run_gravity_points(const PointsRequest& request, const TextSink& write,
                                         const ModelLoaded& loaded, Progress* progress) {
  PointsInput input(request.input);
  const LoadedModel m = load_gravity_field(request.model);
  if (loaded) loaded(m.info);
  gravity::PointsOptions options;
  if (request.track_tolerance_arcsec > 0) options.track_tolerance_rad = units::arcsec_to_rad(request.track_tolerance_arcsec);
  return run_gravity_points(input, m.field, m.info, options, write, progress);
}

gravity::GridRunResult run_gravity_grid(const GridRequest& a, const ModelLoaded& loaded, Progress* progress) {
  gravity::GridSpec spec = grid_spec(a);
  gravity::GridOptions options;
  options.path = gravity::grid_path_from_string(a.path);
  options.threads = a.model.threads;
  if (a.output.empty()) throw InputError("-o/--output FILE (.nc or .csv) is required", {"", {}, "--output"});
  spec.validate();
  // Per-node heights: the file is opened and checked against the nodes before any work.
  std::unique_ptr<GridHeightFile> heights;
  if (!a.height_grid.empty()) {
    heights = std::make_unique<GridHeightFile>(a.height_grid, spec);
    spec.node_heights = heights->source();
  }
  gravity::choose_grid_path(spec, options);  // every check that does not need the model
  check_grid_output(a.output, spec);

  const LoadedModel m = load_gravity_field(a.model);
  if (loaded) loaded(m.info);
  const gravity::GridPath path = gravity::choose_grid_path(spec, options, m.field.max_order());
  const std::unique_ptr<GridFileWriter> writer = open_grid_file(a.output, spec, grid_metadata(a, m.info, m.field.normal(), path));
  gravity::GridRunResult r = grid_result(a, spec, m.info);
  const auto start = std::chrono::steady_clock::now();
  r.synthesis = gravity::synthesize_grid(
      m.field, spec, [&](const gravity::GridRow& row) { writer->write_row(row); }, progress, options);
  writer->commit();
  r.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

gravity::GridPointResult run_geoid_grid_point(const GeoidGridRequest& request) {
  const gravity::GeoidGrid g = read_geoid_grid(request.grid);
  const double lat = parse_latitude_rad(request.lat), lon = parse_longitude_rad(request.lon);
  return gravity::evaluate_grid_point(g, lat, lon, interpolation_from_string(request.interpolation));
}

gravity::SyntheticModelFiles write_synthetic_model(const SyntheticModelRequest& request) {
  if (request.out.empty()) throw InputError("--out PREFIX is required", {"", {}, "--out"});
  const gravity::SyntheticModelOptions options{request.degree, request.seed, 1e-5};
  const gravity::GravityModelData m = gravity::make_synthetic_model(options);
  write_file_atomically(request.out + ".gfc", format_icgem(m));
  write_egm_files(m, request.out);
  return {request.out, m.name, options};
}

}  // namespace meridian::io
