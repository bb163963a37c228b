#pragma once
/// \file nav_html.hpp
/// The report of a marine navigation run (`--report FILE.html`; docs/reports.md): a
/// report::Document (render with render_html). Sections (HTML ids): `summary` (the methods side
/// by side: RMS, max error and mean NEES with truth, final bias ± σ, rejections; the chain
/// parameters), `track` (every method in the x/y plane, east across and north up, at one scale
/// on both axes), `errors` (the per-minute RMS error of every method on one plot; only with
/// truth), `bias` (the velocity-bias estimates against time, north and east, with the ±σ band
/// of the EKF and the smoother), `rejected` (the rejected and the skipped observations),
/// `notes` (warnings and notes). At most 2000 points of a method drawn per plot (every k-th and
/// the last, said in the caption).

#include <string>

#include "meridian/nav/navigation.hpp"
#include "meridian/report/html.hpp"

namespace meridian::report {

/// The report of `result` under `title` (e.g. the configuration's name).
Document nav_document(const nav::Result& result, const std::string& title);

}  // namespace meridian::report
