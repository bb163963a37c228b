#pragma once
/// \file points.hpp
/// The `gravity point` / `gravity points` workflow: ξ, η and N of a model
/// at given points, a chunk at a time so a line of millions of samples
/// streams through in flat memory. The streaming contract:
///
///   PointSource (io: the `lat,lon[,h]` reader, a chunk at a time)
///     → process_points: evaluate_points() per chunk → PointSink (io: the CSV writer)
///     → PointsResult (the input's name, the model, the options and the PointsSummary of
///       every point, built here once) → report::gravity_points_document
///
/// io::run_gravity_points (io/gravity_jobs.hpp) opens the input, loads the
/// model and connects the two ends. No I/O here.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "meridian/core/progress.hpp"
#include "meridian/gravity/gravity_field.hpp"
#include "meridian/gravity/gravity_model.hpp"
#include "meridian/gravity/points_summary.hpp"

namespace meridian::gravity {

/// The model a result came from, as reports name it: what its file states.
struct ModelInfo {
  std::string name;         ///< GravityModelData::name
  std::string source_file;  ///< the file it was read from
  int max_degree = 0;       ///< degree evaluated (after truncation on load)
  int file_max_degree = 0;  ///< degree stated by the file
  double gm_m3_s2 = 0;      ///< GM of the model (m³/s²), as read
  double radius_m = 0;      ///< reference radius a of the expansion (m), as read
  std::string tide_system;    ///< GravityModelData::tide_system; empty when the file does not say
  std::string normalization;  ///< GravityModelData::normalization; empty when the file does not say
  std::string description;    ///< GravityModelData::description
};

/// ModelInfo of a model and the engine built from it.
ModelInfo model_info(const GravityModelData& model, const GravityField& field);

/// What a user must know about a model's metadata before using its
/// numbers: a warning when the file does not state its tide system (or
/// states "unknown"), since N and ξ, η then belong to an unnamed one
/// (mean-tide, zero-tide and tide-free geoids differ by up to decimetres at
/// high latitudes). Empty when there is nothing to warn about.
std::vector<std::string> model_warnings(const ModelInfo& model);

/// The normalisation as reports print it: as stated, or "fully normalised
/// (not stated; the format's default)" — the only one the readers accept.
std::string normalization_text(const ModelInfo& model);

/// `gravity point`: the model's values at one point.
struct PointResult {
  ModelInfo model;
  GeodeticPoint point;
  FieldValues values;
};

/// Options of `gravity points`.
struct PointsOptions {
  /// > 0: the points are consecutive samples of one survey line, evaluated
  /// with evaluate_track (track.hpp): the model at a subset of them and
  /// linear interpolation elsewhere, with the interpolation error in ξ, η
  /// (and the astronomic variant) checked to be ≤ this (rad). ≤ 0 (default):
  /// every point with the full model.
  double track_tolerance_rad = 0;
  /// The same for N (m) when track_tolerance_rad > 0.
  double track_tolerance_geoid_m = 1e-4;

  bool along_track() const noexcept { return track_tolerance_rad > 0; }
};

/// Points per chunk for `options`: 16 384 for scattered points (enough to
/// fill every core's vector batches), 200 000 along a track, whose
/// interpolation starts afresh in every chunk (nodes at both ends), so
/// chunks are long enough that their ends cost little. The chunking is
/// part of the result along a track: the same points in other chunks give
/// other (equally accurate) interpolated values.
std::size_t points_chunk_size(const PointsOptions& options) noexcept;

/// ξ, η, N (and every other FieldValues member) at one chunk of points:
/// GravityField::evaluate on the batch, or evaluate_track with
/// TrackOptions{track_tolerance_rad, track_tolerance_geoid_m} when
/// options.along_track(). Result i belongs to points[i]. Throws InputError
/// for a point outside the model's range (field "points[i]").
std::vector<FieldValues> evaluate_points(const GravityField& field,
                                         std::span<const GeodeticPoint> points,
                                         const PointsOptions& options);

/// Where the points of a `gravity points` run come from, in order, a chunk at a time.
class PointSource {
 public:
  virtual ~PointSource() = default;
  /// Replace `out` with the next points, at most `max` (≥ 1); false when none are left.
  /// Errors are the source's (a reader names the file and line).
  virtual bool next(std::vector<GeodeticPoint>& out, std::size_t max) = 0;
  /// How results name the input ("points.csv", "<stdin>").
  virtual std::string name() const = 0;
  /// Progress in bytes of input: bytes_read() of size_bytes(); a size of 0 (unknown, as for
  /// standard input) makes progress count points instead.
  virtual std::uint64_t bytes_read() const { return 0; }
  virtual std::uint64_t size_bytes() const { return 0; }
};

/// Receives each evaluated chunk in input order; values[i] belongs to points[i].
using PointSink = std::function<void(std::span<const GeodeticPoint> points, std::span<const FieldValues> values)>;

/// `gravity points`: what a run evaluated, everything its writers need (the CSV rows went to
/// the sink as they were computed).
struct PointsResult {
  std::string input;      ///< PointSource::name()
  ModelInfo model;        ///< the model, as its file states it
  PointsOptions options;  ///< as used
  PointsSummary summary;  ///< statistics of every point, a thinned sample for maps
};

/// Read every chunk of `source` (points_chunk_size(options) points), evaluate it
/// (evaluate_points), hand it to `sink`, add it to the summary; return the result of the
/// whole run. `model` describes `field` (model_info). `progress`, when given, is told the
/// bytes read of the source's size ("points (bytes of input)") or, without a size, the points
/// done ("points"); finish() is left to the caller. Errors: the source's, evaluate_points',
/// the sink's, PointsSummary::add's. A chunk with a bad point never reaches the sink: the
/// chunks before it have.
PointsResult process_points(PointSource& source, const GravityField& field, const ModelInfo& model,
                            const PointsOptions& options, const PointSink& sink, Progress* progress = nullptr,
                            std::size_t sample_capacity = PointsSummary::kDefaultSampleCapacity);

}  // namespace meridian::gravity
