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

/// `input` names the file(s) in the header.
Document maglev_reduce_document(const maglev::ReduceResult& r, const maglev::ReduceInput& in,
                                const std::string& input);

Document maglev_calibration_document(const maglev::CalibrationResult& r,
                                     const maglev::CalibrationInput& in, const std::string& input);

}  // namespace meridian::report
