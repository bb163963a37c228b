#include "meridian/gravity/points.hpp"

#include "meridian/gravity/track.hpp"

namespace meridian::gravity {

ModelInfo model_info(const GravityModelData& model, const GravityField& field) {
  return {model.name, model.source_file, field.max_degree(), model.file_max_degree};
}

std::size_t points_chunk_size(const PointsOptions& options) noexcept {
  return options.along_track() ? 200000 : 16384;
}

std::vector<FieldValues> evaluate_points(const GravityField& field,
                                         std::span<const GeodeticPoint> points,
                                         const PointsOptions& options) {
  if (!options.along_track()) return field.evaluate(points);
  TrackOptions to;
  to.tolerance_rad = options.track_tolerance_rad;
  to.tolerance_geoid_m = options.track_tolerance_geoid_m;
  return evaluate_track(field, points, Quantities::All, to).values;
}

}  // namespace meridian::gravity
