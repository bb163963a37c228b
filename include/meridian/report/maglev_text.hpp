#pragma once
/// \file maglev_text.hpp
/// Text reports of the maglev gyro workflows: `maglev reduce` (α_1, N_G, b̂
/// with σ, the plain, median and Huber results, per position the segments
/// kept and rejected, variances before and after) and `maglev calibrate`.
/// Angles in DMS and arcseconds, currents in A.

#include <string>

#include "meridian/maglev/calibration.hpp"
#include "meridian/maglev/reduce.hpp"

namespace meridian::report {

std::string maglev_reduce_text(const maglev::ReduceResult& r);
std::string maglev_calibration_text(const maglev::CalibrationResult& r);

}  // namespace meridian::report
