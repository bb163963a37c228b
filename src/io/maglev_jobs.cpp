#include "meridian/io/maglev_jobs.hpp"

#include <utility>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/io/source_map.hpp"

namespace meridian::io {
namespace {

// The constants of a reduction, each from the last of: the constants file, the calibration
// (K and I* only), the values given.
MaglevConstants merged_constants(const MaglevReduceSetup& setup) {
  MaglevConstants k;
  if (!setup.constants_file.empty()) k = read_maglev_constants(setup.constants_file);
  if (!setup.calibration_file.empty()) {
    const MaglevConstants c = read_maglev_constants(setup.calibration_file);
    if (c.scale_A_s_per_rad) k.scale_A_s_per_rad = c.scale_A_s_per_rad;
    if (c.constant_deviation_A) k.constant_deviation_A = c.constant_deviation_A;
  }
  const MaglevConstants& g = setup.given;
  if (g.scale_A_s_per_rad) k.scale_A_s_per_rad = g.scale_A_s_per_rad;
  if (g.latitude_rad) k.latitude_rad = g.latitude_rad;
  if (g.circle_reading1_rad) k.circle_reading1_rad = g.circle_reading1_rad;
  if (g.constant_deviation_A) k.constant_deviation_A = g.constant_deviation_A;
  return k;
}

// Both positions' series: one file with a position column, or one file per position.
std::pair<MaglevSeriesFile, MaglevSeriesFile> read_positions(const std::vector<std::string>& files) {
  if (files.size() == 1) return read_maglev_two_positions(files[0]);
  if (files.size() == 2) return {read_maglev_series_file(files[0], 1), read_maglev_series_file(files[1], 2)};
  throw InputError("give one file with a position column, or two files (position 1, position 2)",
                   {"", std::nullopt, "files"});
}

// Where the samples of `position` ("position1") were read: a sample's time and current at its
// line and column, the whole series at its file and column, any other field of the position
// (its processing: "position1.segment_length") at its file with the field kept.
void add_series(SourceMap& sources, const std::string& position, const MaglevSeriesFile& f) {
  for (const auto& [member, column] : {std::pair<const char*, const char*>{"time_s", "time"},
                                       std::pair<const char*, const char*>{"current_A", "current"}}) {
    const std::string array = position + "." + member;
    sources.add_rows(array, [&f, column = std::string(column)](std::size_t i, const std::string&) {
      return ErrorContext{f.file, i < f.lines.size() ? std::optional<int>(f.lines[i]) : std::nullopt, column};
    });
    sources.add_place(array, {f.file, std::nullopt, column});
  }
  sources.add_document(position, f.file, {}, position);
}

}  // namespace

maglev::ReduceInput maglev_reduce_input(const MaglevReduceSetup& setup) {
  const MaglevConstants k = merged_constants(setup);
  const MaglevArgumentNames& n = setup.names;
  if (!k.scale_A_s_per_rad)
    throw InputError(fmt::format("the scale K is needed: {}, {} or {}", n.scale, n.constants_file,
                                 n.calibration_file),
                     {"", std::nullopt, n.scale});
  if (!k.latitude_rad)
    throw InputError(fmt::format("the latitude is needed: {} or {}", n.latitude, n.constants_file),
                     {"", std::nullopt, n.latitude});
  maglev::ReduceInput in;
  in.scale_A_s_per_rad = *k.scale_A_s_per_rad;
  in.latitude_rad = *k.latitude_rad;
  in.circle_reading1_rad = {k.circle_reading1_rad.value_or(0.0), setup.reading1_sigma_rad};
  in.chain = setup.chain;
  in.options = setup.options;
  in.options.prior_bias_A = k.constant_deviation_A;
  return in;
}

maglev::ReduceResult run_maglev_reduce_files(const std::vector<std::string>& files,
                                             const MaglevReduceSetup& setup, Progress* progress) {
  maglev::ReduceInput in = maglev_reduce_input(setup);
  const auto [f1, f2] = read_positions(files);
  for (const std::string& f : files) in.source += (in.source.empty() ? "" : ", ") + f;
  in.position1 = f1.series;
  in.position2 = f2.series;
  SourceMap sources;
  add_series(sources, "position1", f1);
  add_series(sources, "position2", f2);
  return located(sources, [&] { return maglev::process(in, progress); });
}

maglev::ReduceResult run_maglev_reduce(const MaglevReduceSetup& setup,
                                       maglev::PositionSeries position1,
                                       maglev::PositionSeries position2, Progress* progress) {
  maglev::ReduceInput in = maglev_reduce_input(setup);
  in.position1 = std::move(position1);
  in.position2 = std::move(position2);
  return maglev::process(in, progress);
}

maglev::SeriesDenoising run_maglev_denoise_file(const std::string& path,
                                                const maglev::DenoiseOptions& options) {
  const MaglevSeriesFile f = read_maglev_series_file(path, 0);
  SourceMap sources;
  sources.add_document(f.file, {});  // every field at the file, its path kept
  return located(sources, [&] { return maglev::denoise_series(f.series, options); });
}

maglev::CalibrationResult run_maglev_calibrate_file(const std::string& path, double latitude_rad,
                                                    double alpha,
                                                    std::optional<double> nominal_scale_A_s_per_rad) {
  maglev::CalibrationInput in = read_maglev_calibration_table(path);
  in.source = path;
  in.latitude_rad = latitude_rad;
  in.alpha = alpha;
  in.nominal_scale_A_s_per_rad = nominal_scale_A_s_per_rad;
  SourceMap sources;
  sources.add_document(path, {});  // every field at the file, its path kept
  return located(sources, [&] { return maglev::calibrate(in); });
}

}  // namespace meridian::io
