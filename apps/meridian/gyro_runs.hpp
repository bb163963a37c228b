#pragma once
// Running a gyro file through the library, shared by `gyro reduce`,
// `gyro campaign` and `demo`: errors raised while processing get the file
// and line of the field they name.

#include <string>
#include <vector>

#include "meridian/core/progress.hpp"
#include "meridian/gyro/campaign.hpp"
#include "meridian/gyro/determination.hpp"
#include "meridian/gyro/instrument_spec.hpp"
#include "meridian/io/gyro_files.hpp"

namespace meridian::cli {

struct ReducedFile {
  io::GyroReduceFile file;
  gyro::ResolvedInstrument instrument;
  std::vector<gyro::DeterminationResult> results;  ///< parallel to file.determinations
};

/// Read a reduce file and reduce every determination.
ReducedFile reduce_file(const std::string& path, Progress* progress = nullptr);

/// Process a campaign already read from its file.
gyro::CampaignResult process_campaign_file(const io::CampaignFile& f, Progress* progress = nullptr);

}  // namespace meridian::cli
