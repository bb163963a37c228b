#pragma once
/// \file maglev_html.hpp
/// `--report FILE.html` of `maglev reduce` and `maglev calibrate`: a
/// report::Document (render with render_html). The reduce report shows the
/// result (processed, plain, median, Huber), per position the raw and the
/// cleaned series (at most 2000 points each, every k-th sample) with the
/// rejected segments shaded, and the table of segments; the calibration
/// report the position means with the fitted lines and the residuals.

#include <string>

#include "meridian/maglev/calibration.hpp"
#include "meridian/maglev/reduce.hpp"
#include "meridian/report/html.hpp"

namespace meridian::report {

/// The header names the Result's source (the files read).
Document maglev_reduce_document(const maglev::ReduceResult& r);

Document maglev_calibration_document(const maglev::CalibrationResult& r);

}  // namespace meridian::report
