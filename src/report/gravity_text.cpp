#include "meridian/report/gravity_text.hpp"

#include <iterator>

#include <fmt/format.h>

#include "meridian/core/units.hpp"

namespace meridian::report {

namespace {

std::string model_lines(const gravity::ModelInfo& m) {
  return fmt::format("model {} (degree {}, {})\nmodel GM {} m^3/s^2, reference radius {} m, tide system {}, normalisation {}\n",
                     m.name, m.max_degree, m.source_file, m.gm_m3_s2, m.radius_m,
                     m.tide_system.empty() ? "not stated" : m.tide_system, gravity::normalization_text(m));
}

void append_warnings(std::string& out, const gravity::ModelInfo& m) {
  for (const std::string& w : gravity::model_warnings(m)) fmt::format_to(std::back_inserter(out), "warning: {}\n", w);
}

}  // namespace

std::string model_text(const gravity::ModelInfo& model) {
  std::string out = model_lines(model);
  append_warnings(out, model);
  return out;
}

std::string model_warnings_text(const gravity::ModelInfo& model) {
  std::string out;
  append_warnings(out, model);
  return out;
}

std::string gravity_point_text(const gravity::PointResult& r) {
  std::string out = model_lines(r.model);
  fmt::format_to(std::back_inserter(out),
                 "point lat {:.9f} deg, lon {:.9f} deg, h {:.3f} m\n"
                 "xi_arcsec  {:.9f}\neta_arcsec {:.9f}\ngeoid_m    {:.9f}\n",
                 units::rad_to_deg(r.point.lat_rad), units::rad_to_deg(r.point.lon_rad), r.point.height_m,
                 // + 0.0: a zero printed without a sign (ξ = −0 when nothing above degree 0 is kept)
                 units::rad_to_arcsec(r.values.xi_rad) + 0.0, units::rad_to_arcsec(r.values.eta_rad) + 0.0,
                 r.values.geoid_m + 0.0);
  append_warnings(out, r.model);
  return out;
}

std::string geoid_grid_text(const gravity::GridPointResult& r) {
  std::string out = fmt::format("grid {} ({})\nmodel {}; degree, GM, reference radius, tide system, normalisation: not stated\n"
                                "geoid_m    {:.6f}\n",
                                r.grid_file, gravity::to_string(r.interpolation),
                                r.grid.model ? *r.grid.model : "not stated", r.geoid_m);
  const char* method = gravity::GridDeflection{}.method;
  if (r.fallback)
    fmt::format_to(std::back_inserter(out), "xi_arcsec  {:.3f}  [{}]\neta_arcsec {:.3f}  [{}]\n",
                   units::rad_to_arcsec(r.fallback->xi_rad), method, units::rad_to_arcsec(r.fallback->eta_rad), method);
  else
    fmt::format_to(std::back_inserter(out), "xi_arcsec  unavailable  [{}]\neta_arcsec unavailable  [{}]\nnote: {}\n",
                   method, method, r.fallback_unavailable);
  for (const std::string& n : r.notes) fmt::format_to(std::back_inserter(out), "note: {}\n", n);
  for (const std::string& w : r.grid.warnings) fmt::format_to(std::back_inserter(out), "warning: {}\n", w);
  return out;
}

std::string gravity_grid_text(const gravity::GridRunResult& r) {
  std::string names;
  for (const gravity::GridFileQuantity& q : r.quantities)
    names += fmt::format("{}{} [{}]", names.empty() ? "" : ", ", q.name, q.units);
  const gravity::GridSynthesisResult& s = r.synthesis;
  // A global gridline .gtx leaves out the repeated column at W + 360°: say what the file holds.
  const std::string stored =
      r.stored_columns == s.columns
          ? std::string()
          : fmt::format(" ({} x {} stored: the column at {}° repeats the one at {}° and is left out, readers wrap)",
                        r.stored_columns, s.rows, r.spec.east_deg, r.spec.west_deg);
  return fmt::format("wrote {} ({}): {} x {} nodes (lon x lat, {} registration){}, {}\n"
                     "heights {}\npath {}{}, {}, {:.2f} s\n",
                     r.output, r.format_label, s.columns, s.rows, gravity::to_string(r.spec.registration), stored, names,
                     r.height_grid.empty() ? fmt::format("{} m at every node", r.spec.height_m)
                                           : "per node from " + r.height_grid,
                     gravity::to_string(s.path_used),
                     s.fft_length ? fmt::format(" (one real FFT of length {} per parallel and quantity)", s.fft_length)
                     : s.per_node_heights ? std::string(" (every node as a scattered point: per-node heights)")
                                          : std::string(" (GravityCircle per parallel)"),
                     s.per_node_heights ? std::string("parallels in order, each one's nodes over the threads")
                                        : fmt::format("{} thread(s) over parallels", s.threads),
                     r.elapsed_s);
}

std::string synthetic_model_text(const gravity::SyntheticModelFiles& r) {
  return fmt::format("wrote {0}.gfc, {0}.egm, {0}.egm.cof (model {1}, degree {2}, seed {3})\n", r.prefix,
                     r.model_name, r.options.max_degree, r.options.seed);
}

}  // namespace meridian::report
