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
#include "meridian/gyro/orientations.hpp"
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

/// `meridian gyro orientations --report`: the result sheet (成果表) of
/// independent orientations of one line — the mean grid azimuth and its σ
/// with the parts the orientations share (gyro/error_sources.hpp), each
/// orientation's T, E, programme and own checks, the traverse azimuth and
/// mean minus traverse, signatures — then the checks and notes. Labels in the
/// language of orientation 1's record (RecordSheet::language: "zh" adds the
/// Chinese terms). `orientations` are the campaign results combined into
/// `result`, in its order; throws InputError when their number differs.
Document gyro_orientations_document(const gyro::OrientationsResult& result,
                                    const std::vector<gyro::CampaignResult>& orientations);

}  // namespace meridian::report
