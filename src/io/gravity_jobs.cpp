#include "meridian/io/gravity_jobs.hpp"

#include <filesystem>
#include <iostream>
#include <vector>

#include "meridian/core/error.hpp"
#include "meridian/io/gravity_csv.hpp"
#include "meridian/io/gravity_points.hpp"

namespace meridian::io {

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

gravity::PointsSummary run_gravity_points(PointsInput& input, const gravity::GravityField& field,
                                          const gravity::PointsOptions& options,
                                          const TextSink& write, Progress* progress,
                                          std::size_t sample_capacity) {
  gravity::PointsSummary summary(sample_capacity);
  write(gravity_points_csv_header());
  GravityPointReader reader(input.stream(), input.name());
  const std::size_t chunk = gravity::points_chunk_size(options);
  std::vector<gravity::GeodeticPoint> points;
  std::string text;
  std::size_t done = 0;
  while (reader.next(points, chunk)) {
    const std::vector<gravity::FieldValues> values =
        gravity::evaluate_points(field, points, options);
    text.clear();
    append_gravity_points_csv(text, points, values);
    write(text);
    summary.add(points, values);
    done += points.size();
    if (input.size_bytes() > 0)
      report_progress(progress, reader.bytes_read(), input.size_bytes(), "points (bytes of input)");
    else
      report_progress(progress, done, 0, "points");
  }
  return summary;
}

}  // namespace meridian::io
