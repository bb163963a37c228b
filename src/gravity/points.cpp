#include "meridian/gravity/points.hpp"

#include <fmt/format.h>

#include "meridian/gravity/track.hpp"

namespace meridian::gravity {

ModelInfo model_info(const GravityModelData& model, const GravityField& field) {
  return {model.name,     model.source_file, field.max_degree(),    model.file_max_degree, model.gm_m3_s2,
          model.radius_m, model.tide_system, model.normalization, model.description};
}

std::vector<std::string> model_warnings(const ModelInfo& model) {
  std::vector<std::string> w;
  if (model.tide_system.empty() || model.tide_system == "unknown")
    w.push_back(fmt::format(
        "the model file {} its tide system: the geoid heights and deflections are in the system of its "
        "coefficients, whichever that is (mean-tide, zero-tide and tide-free geoids differ by up to decimetres at "
        "high latitudes); find it in the model's documentation before combining them with other heights",
        model.tide_system.empty() ? "does not state" : "gives \"unknown\" as"));
  return w;
}

std::string normalization_text(const ModelInfo& model) {
  return model.normalization.empty() ? "fully normalised (not stated; the format's default)" : model.normalization;
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

PointsResult process_points(PointSource& source, const GravityField& field, const ModelInfo& model,
                            const PointsOptions& options, const PointSink& sink, Progress* progress,
                            std::size_t sample_capacity) {
  PointsResult result{source.name(), model, options, PointsSummary(sample_capacity)};
  const std::size_t chunk = points_chunk_size(options);
  std::vector<GeodeticPoint> points;
  std::size_t done = 0;
  while (source.next(points, chunk)) {
    const std::vector<FieldValues> values = evaluate_points(field, points, options);
    sink(points, values);
    result.summary.add(points, values);
    done += points.size();
    if (source.size_bytes() > 0)
      report_progress(progress, source.bytes_read(), source.size_bytes(), "points (bytes of input)");
    else
      report_progress(progress, done, 0, "points");
  }
  return result;
}

}  // namespace meridian::gravity
