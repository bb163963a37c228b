#pragma once
/// \file maglev_text.hpp
/// Text reports of the maglev gyro workflows: `maglev reduce` (α_1, N_G, b̂
/// with σ, the plain, median and Huber results, per position the segments
/// kept and rejected, variances before and after), `maglev calibrate` and
/// `maglev denoise` (the comment above its CSV).
/// Angles in DMS and arcseconds, currents in A.

#include <string>

#include "meridian/maglev/calibration.hpp"
#include "meridian/maglev/denoise.hpp"
#include "meridian/maglev/reduce.hpp"

namespace meridian::report {

std::string maglev_reduce_text(const maglev::ReduceResult& r);
std::string maglev_calibration_text(const maglev::CalibrationResult& r);
/// Two lines on a denoising (wavelet, level used, mode, rule, threshold kind, noise σ, λ per
/// level, level 1 first): the comment heading `maglev denoise`'s CSV.
std::string maglev_denoise_text(const maglev::DenoiseResult& r);

}  // namespace meridian::report
