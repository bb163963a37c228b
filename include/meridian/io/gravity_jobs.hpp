#pragma once
/// \file gravity_jobs.hpp
/// The runners of the gravity commands: read the input, load the model (io/gravity_model_lookup.hpp)
/// and build its engine, call the gravity module, and return its Result for the writers
/// (report/gravity_*.hpp). Shared by `meridian gravity point | points | grid | geoid-grid |
/// synth-model` and the Python package (models: load_gravity_field).
///
/// A request holds the options as the user gave them (angles as typed, names, paths); the
/// runner parses and checks them, in the order the CLI documents its errors.

#include <cstdint>
#include <fstream>
#include <functional>
#include <istream>
#include <string>
#include <string_view>

#include "meridian/core/progress.hpp"
#include "meridian/gravity/geoid_grid.hpp"
#include "meridian/gravity/gravity_field.hpp"
#include "meridian/gravity/grid_run.hpp"
#include "meridian/gravity/points.hpp"
#include "meridian/gravity/points_summary.hpp"
#include "meridian/gravity/synthetic.hpp"

namespace meridian::io {

/// A model to load and the engine to build from it.
struct ModelRequest {
  std::string model;     ///< a file (.gfc, .egm) or a name found on gravity_search_path()
  int max_degree = -1;   ///< truncation on load; −1 (or above the file's): the file's degree
  unsigned threads = 0;  ///< threads of the engine's batches (0 = all cores)
};

/// A model ready to evaluate: what its file states and the engine built from it.
struct LoadedModel {
  gravity::ModelInfo info;
  gravity::GravityField field;
};

/// The engine for `data` (its coefficients move in: no copy of 38 MB at degree 2190) with
/// `threads`, and its ModelInfo. Throws as gravity::GravityField.
LoadedModel prepare_model(gravity::GravityModelData&& data, unsigned threads = 0);

/// load_model(request.model, {request.max_degree, −1}) (gravity_model_lookup.hpp), then
/// prepare_model. Throws load_model's errors (InputError field "--model" when not found).
LoadedModel load_gravity_field(const ModelRequest& request);

/// Called once the model is loaded, before the work starts (the CLI prints the model's
/// lines to stderr then, so they precede any error of the run).
using ModelLoaded = std::function<void(const gravity::ModelInfo&)>;

/// `gravity point`: a model at one point.
struct PointRequest {
  ModelRequest model;
  std::string lat, lon;  ///< as typed: decimal degrees or DMS (parse_latitude_rad, parse_longitude_rad)
  double h_m = 0;        ///< ellipsoidal height (m)
};

/// Load the model, parse the point, evaluate every quantity. Errors: load_gravity_field's,
/// the parsers' (field "latitude", "longitude"), GravityField::evaluate's.
gravity::PointResult run_gravity_point(const PointRequest& request);

/// The input of a points run: a file, or standard input.
class PointsInput {
 public:
  /// Open `path`; "" or "-" is standard input. Throws IoError
  /// ("cannot open input file", naming the path) when it cannot be opened.
  explicit PointsInput(const std::string& path);
  PointsInput(const PointsInput&) = delete;
  PointsInput& operator=(const PointsInput&) = delete;

  std::istream& stream() noexcept { return *in_; }
  /// The path, or "<stdin>": how errors name the input.
  const std::string& name() const noexcept { return name_; }
  /// Size of the file in bytes; 0 when unknown (standard input).
  std::uint64_t size_bytes() const noexcept { return size_; }

 private:
  std::ifstream file_;
  std::istream* in_;
  std::string name_;
  std::uint64_t size_ = 0;
};

/// Where output text goes, chunk by chunk (a file writer, stdout, a string).
using TextSink = std::function<void(std::string_view)>;

/// Write the CSV header (gravity_csv.hpp), then stream `input` through
/// gravity::process_points with its rows as the source (GravityPointReader) and the CSV
/// writer as the sink (`write`). Errors: those of GravityPointReader (source and line), of
/// gravity::process_points and of `write`. A chunk with a bad row is never written: the rows
/// of earlier chunks have been.
gravity::PointsResult run_gravity_points(
    PointsInput& input, const gravity::GravityField& field, const gravity::ModelInfo& model,
    const gravity::PointsOptions& options, const TextSink& write, Progress* progress = nullptr,
    std::size_t sample_capacity = gravity::PointsSummary::kDefaultSampleCapacity);

/// `gravity points`: a model at the `lat,lon[,h]` rows of a file or standard input.
struct PointsRequest {
  ModelRequest model;
  std::string input;                   ///< CSV of lat,lon[,h]; "" or "-": standard input
  double track_tolerance_arcsec = 0;   ///< > 0: the rows are one track, interpolated (PointsOptions)
};

/// Open the input (IoError first, before the model is loaded), load the model, tell
/// `loaded`, then run_gravity_points with the CSV going to `write`. `progress` as
/// gravity::process_points; finish() is left to the caller.
gravity::PointsResult run_gravity_points(const PointsRequest& request, const TextSink& write,
                                         const ModelLoaded& loaded = {}, Progress* progress = nullptr);

/// `gravity grid`: a model on a regular grid, written to a file.
struct GridRequest {
  ModelRequest model;
  std::string region;                        ///< GMT W/E/S/N, g or d (gravity::parse_grid_region)
  std::string spacing;                       ///< GMT 30s, 5m, 0.5d, X/Y (gravity::parse_grid_spacing)
  std::string quantities = "xi,eta,geoid";   ///< comma-separated (gravity::parse_grid_quantities)
  bool pixel = false;                        ///< pixel (cell-centre) registration, else gridline
  double height_m = 0;                       ///< of every node, unless height_grid
  std::string height_grid;                   ///< FILE.nc[?VAR] of per-node heights (GridHeightFile)
  std::string path = "auto";                 ///< auto | fft | parallel
  std::string output;                        ///< .nc, .gtx or .csv (gravity_grid_files.hpp)
};

/// Every check that needs no model first (region, spacing, quantities, path, the height grid
/// against the nodes, the output path: InputError/IoError before any loading), then load the
/// model, tell `loaded`, open the output (created as a temporary), synthesise
/// (gravity::synthesize_grid) row by row into it and commit it. The NetCDF `history` is the
/// command line the request stands for. `progress` gets parallels done; finish() is left to
/// the caller.
gravity::GridRunResult run_gravity_grid(const GridRequest& request, const ModelLoaded& loaded = {},
                                        Progress* progress = nullptr);

/// `gravity geoid-grid`: a geoid grid file at one point.
struct GeoidGridRequest {
  std::string grid;                       ///< .gtx or .pgm (gravity_geoid_grid.hpp)
  std::string lat, lon;                   ///< as typed, decimal degrees or DMS
  std::string interpolation = "bicubic";  ///< bicubic | bilinear
};

/// Read the grid, parse the point and the interpolation (InputError, field "--interpolation"),
/// gravity::evaluate_grid_point.
gravity::GridPointResult run_geoid_grid_point(const GeoidGridRequest& request);

/// `gravity synth-model`: a synthetic model written as PREFIX.gfc, PREFIX.egm, PREFIX.egm.cof.
struct SyntheticModelRequest {
  int degree = 360;
  std::uint64_t seed = 1;
  std::string out;  ///< PREFIX
};

/// gravity::make_synthetic_model, written with format_icgem and write_egm_files (each file
/// atomically). InputError (field "--out") without a prefix.
gravity::SyntheticModelFiles write_synthetic_model(const SyntheticModelRequest& request);

}  // namespace meridian::io
