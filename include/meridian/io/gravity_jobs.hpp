#pragma once
/// \file gravity_jobs.hpp
/// Running `gravity points` from input to output: the points are read a
/// chunk at a time (GravityPointReader), evaluated (gravity::evaluate_points),
/// written as CSV (gravity_csv.hpp) and summarised (gravity::PointsSummary),
/// so memory stays flat however long the input. The caller loads the model
/// once and says where the CSV goes.

#include <cstdint>
#include <fstream>
#include <functional>
#include <istream>
#include <string>
#include <string_view>

#include "meridian/core/progress.hpp"
#include "meridian/gravity/gravity_field.hpp"
#include "meridian/gravity/points.hpp"
#include "meridian/gravity/points_summary.hpp"

namespace meridian::io {

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

/// Write the CSV header, then read, evaluate and write every chunk
/// (gravity::points_chunk_size(options) points) of `input`, and return the
/// summary of all points. `progress`, when given, is told the bytes read of
/// the input's size ("points (bytes of input)") or, for standard input, the
/// points done ("points"); finish() is left to the caller. Errors: those of
/// GravityPointReader (source and line), of gravity::evaluate_points and of
/// `write`. A chunk with a bad row is never written: the rows of earlier
/// chunks have been.
gravity::PointsSummary run_gravity_points(
    PointsInput& input, const gravity::GravityField& field, const gravity::PointsOptions& options,
    const TextSink& write, Progress* progress = nullptr,
    std::size_t sample_capacity = gravity::PointsSummary::kDefaultSampleCapacity);

}  // namespace meridian::io
