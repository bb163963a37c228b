#pragma once
/// \file points.hpp
/// The `gravity point` / `gravity points` workflow: ξ, η and N of a model
/// at given points, a chunk at a time so a line of millions of samples
/// streams through in flat memory.
///
///   points (io::GravityPointReader, a chunk at a time) → evaluate_points()
///   → io CSV writer, PointsSummary (points_summary.hpp) over the whole run
///   → report::gravity_points_document
///
/// (io::run_gravity_points does the loop.) No I/O here.

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "meridian/gravity/gravity_field.hpp"
#include "meridian/gravity/gravity_model.hpp"

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

}  // namespace meridian::gravity
