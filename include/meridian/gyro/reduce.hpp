#pragma once
/// \file reduce.hpp
/// The `gyro reduce` workflow: the determinations of one station reduced to
/// gyro north N_G, each with its σ, by the requested method or by every
/// applicable one side by side.
///
///   ReduceInput (io::read_gyro_reduce_file) → process() → ReduceResult
///   → report::reduce_text / reduce_to_json / gyro_reduce_document (they take only the result)

#include <vector>

#include "meridian/core/dms.hpp"
#include "meridian/core/progress.hpp"
#include "meridian/gyro/determination.hpp"
#include "meridian/gyro/instrument_spec.hpp"

namespace meridian::gyro {

/// The determinations of one station with the instrument that made them.
struct ReduceInput {
  InstrumentSpec instrument;
  double latitude_rad = 0.0;                     ///< geodetic latitude φ of the station
  std::vector<DeterminationInput> determinations;
  ReduceOptions options;
  /// How the file booked its circle angles (its `angle_unit:`), so results
  /// can be printed in the book's unit; the values above are radians.
  AngleUnit angle_unit = AngleUnit::Dms;
  /// The field book it was read from, as named (for the reports; empty when
  /// the Input is built in code). Never opened by the library.
  std::string file;
};

struct ReduceResult {
  /// What was reduced (a copy of the Input): the writers show its file, its
  /// observations and its angle unit.
  ReduceInput input;
  ResolvedInstrument instrument;                 ///< constants at the station latitude
  std::vector<DeterminationResult> determinations;  ///< parallel to ReduceInput::determinations
};

/// Resolve the instrument at the station latitude and reduce every
/// determination. Errors carry field paths ("instrument",
/// "determinations[2].crossings[0].times_s"; the runner's io::SourceMap adds
/// the file and line). `progress`, when given, is told about each determination.
ReduceResult process(const ReduceInput& in, Progress* progress = nullptr);

}  // namespace meridian::gyro
