#pragma once
/// \file gyro_writers.hpp
/// Writers of gyro field-book files in the YAML formats that the readers
/// accept (docs/file-formats.md). Circle angles are written in the input's
/// angle_unit (DMS strings with 4 decimals of arc-seconds by default; deg and
/// gon as round-trip numbers; ddd.mmss with 4 decimals of seconds), times and
/// readings with round-trip precision, so reading a written file gives back
/// the same values (to 1e-4″ for angles) and the same angle_unit.

#include <string>

#include "meridian/io/gyro_files.hpp"
#include "meridian/io/gyro_simulate.hpp"

namespace meridian::io {

/// A `meridian gyro reduce` file. `header` is written as leading comment
/// lines (e.g. the command and the truth of a simulation). The reduce
/// options are not written (the readers' defaults apply).
std::string reduce_file_yaml(const gyro::ReduceInput& input, const std::string& header = {});

/// A `meridian gyro campaign` file.
std::string campaign_file_yaml(const gyro::CampaignInput& campaign, const std::string& header = {});

/// The text of a simulated book (`meridian gyro simulate`): a reduce file (a station's runs) or a
/// campaign file, headed by "Simulated by: <command line>" and the truth, one comment line each.
std::string simulated_book_yaml(const SimulatedBook& simulated);

/// A commented campaign field book to start from (`meridian gyro template`):
/// every field explained with its unit, both modes, motor-off runs, the
/// 3-2-3 programme, angle_unit and m:ss.s times. An invented but consistent
/// job: read_campaign_file reads it and it processes with its checks passing.
std::string campaign_template_yaml();

/// The same for the runs of one station (`meridian gyro template --kind
/// reduce`), read by read_gyro_reduce_file.
std::string reduce_template_yaml();

}  // namespace meridian::io
