#pragma once
/// \file gyro_files.hpp
/// Readers for gyro-theodolite field-book files (YAML, or JSON as is).
/// The formats are documented in docs/file-formats.md. Readers turn a file
/// into plain structs; errors name the file, line and field.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "meridian/core/error.hpp"
#include "meridian/gyro/campaign.hpp"
#include "meridian/gyro/determination.hpp"
#include "meridian/gyro/instrument_spec.hpp"

namespace meridian::io {

/// Line (1-based) of each determination, point and section of a file, by
/// field path ("determinations[2]", "line.determinations[0]", …).
using FieldLines = std::map<std::string, int>;

/// Give an error thrown while processing a file's contents the file name
/// and the line of the innermost recorded field that contains its field.
void locate_error(Error& e, const std::string& file, const FieldLines& lines);

/// Contents of a `meridian gyro reduce` file.
struct GyroReduceFile {
  std::string file;
  gyro::InstrumentSpec instrument;
  double latitude_rad = 0.0;                       ///< station latitude φ
  std::vector<gyro::DeterminationInput> determinations;
  FieldLines lines;
  gyro::ReduceOptions options;
};

/// Read a reduce file. Throws ParseError/InputError with file, line, field.
GyroReduceFile read_gyro_reduce_file(const std::filesystem::path& path);

/// Contents of a `meridian gyro campaign` file.
struct CampaignFile {
  std::string file;
  gyro::CampaignInput campaign;
  FieldLines lines;
};

CampaignFile read_campaign_file(const std::filesystem::path& path);

}  // namespace meridian::io
