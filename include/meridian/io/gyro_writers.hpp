#pragma once
/// \file gyro_writers.hpp
/// Writers of gyro field-book files in the YAML formats that the readers
/// accept (docs/file-formats.md). Angles are written as DMS strings with
/// 4 decimals of arc-seconds, times and readings with round-trip precision,
/// so reading a written file gives back the same values (to 1e-4″ for angles).

#include <string>

#include "meridian/io/gyro_files.hpp"

namespace meridian::io {

/// A `meridian gyro reduce` file. `header` is written as leading comment
/// lines (e.g. the command and the truth of a simulation). The reduce
/// options are not written (the readers' defaults apply).
std::string reduce_file_yaml(const gyro::ReduceInput& input, const std::string& header = {});

/// A `meridian gyro campaign` file.
std::string campaign_file_yaml(const gyro::CampaignInput& campaign, const std::string& header = {});

}  // namespace meridian::io
