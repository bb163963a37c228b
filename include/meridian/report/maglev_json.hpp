#pragma once
/// \file maglev_json.hpp
/// JSON of the maglev gyro workflows (docs/maglev-gyro.md, "JSON"): keys
/// carry their units (`alpha1_arcsec`, `sigma_arcsec`, `north_deg`,
/// `mean_A`, `variance_A2`). Segments list begin/end sample indices
/// (0-based, end exclusive), their times, statistics and `kept`.
/// The calibration JSON is also the stored calibration that `maglev reduce
/// --calibration` reads (scale_A_s_per_rad, constant_deviation_A).

#include <nlohmann/json.hpp>

#include "meridian/maglev/calibration.hpp"
#include "meridian/maglev/reduce.hpp"

namespace meridian::report {

/// The Result carries the constants and options used and the series (the segments' times).
nlohmann::json maglev_reduce_to_json(const maglev::ReduceResult& r);
nlohmann::json maglev_calibration_to_json(const maglev::CalibrationResult& r);

}  // namespace meridian::report
