#pragma once
/// \file dov_html.hpp
/// `dov process --report FILE.html`: a report::Document (render with render_html) of a
/// deflection-of-the-vertical line. Sections (HTML ids): `summary` (the smoothed figures, the
/// consistency check of the mean NIS against its 95 % interval, RMS errors when truth was
/// given), `profile` (η and ξ against time: the global model's η_G, ξ_G, the filtered and the
/// smoothed estimate with its ±σ band, and the true η, ξ when the line carried them),
/// `innovations` (ν_E, ν_N in a ±2√S band), `notes`. Angles in arcseconds, signs of η, ξ as
/// geodesy/frames.hpp; at most 2000 epochs drawn per plot (every k-th, said in the caption).

#include <cstddef>
#include <string>

#include "meridian/dov/deflection.hpp"
#include "meridian/report/html.hpp"

namespace meridian::report {

/// The epochs a report of a streamed line needs kept (dov::EpochOutputs::keep_epochs): twice
/// the 2000 it draws per plot, so that its own stride still draws every k-th epoch of the line.
inline constexpr std::size_t kDovReportEpochs = 4000;

/// The report of `result`: its origin in the header (the configuration, the line file, and the
/// gravity model that gave η_G, ξ_G — or the line's model columns), its options, summary,
/// epochs and notes. result.epoch_stride > 1 says result.epochs is already thinned to one epoch
/// in that many (a streamed line; the captions count both thinnings).
Document dov_document(const dov::Result& result);

}  // namespace meridian::report
