#pragma once
/// \file gyro_html.hpp
/// HTML report documents for the gyro workflows: the mapping from result
/// structs (each carries the Input it came from: the file, and the
/// observations for the plots) to a report::Document. Render with render_html().

#include <string>
#include <vector>

#include "meridian/gyro/campaign.hpp"
#include "meridian/gyro/determination.hpp"
#include "meridian/gyro/instrument_spec.hpp"
#include "meridian/gyro/reduce.hpp"
#include "meridian/report/html.hpp"

namespace meridian::report {

/// `meridian gyro reduce`: one section per determination with the
/// oscillation plot (observations and fitted model), residuals, zero-position
/// runs and, for `method: all`, every method side by side.
Document gyro_reduce_document(const gyro::ReduceResult& result);

/// `meridian gyro campaign`: result and azimuth chain, checks, calibration,
/// the line's determinations, then every determination in detail.
Document gyro_campaign_document(const gyro::CampaignResult& result);

}  // namespace meridian::report
