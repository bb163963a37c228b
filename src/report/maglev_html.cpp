#include "meridian/report/maglev_html.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "meridian/core/angle.hpp"
#include "meridian/core/dms.hpp"
#include "meridian/core/units.hpp"

namespace meridian::report {
namespace {
using nlohmann::json;

constexpr std::size_t kMaxPoints = 2000;

std::string solution_text(const maglev::TwoPositionSolution& s) {
  return fmt::format("α1 {} ± {:.3f}\", N_G {} ± {:.3f}\", b {:.9g} A",
                     format_dms(Angle::radians(s.alpha1_rad.value), {3, true, true}),
                     units::rad_to_arcsec(s.alpha1_rad.sigma),
                     format_direction_dms(Angle::radians(s.north_rad.value), {3, true, false}),
                     units::rad_to_arcsec(s.north_rad.sigma), s.bias_A.value);
}

Plot series_plot(const char* name, const maglev::PositionResult& p) {
  const maglev::PositionSeries& s = p.series;
  const std::size_t n = s.current_A.size();
  const std::size_t step = std::max<std::size_t>(1, (n + kMaxPoints - 1) / kMaxPoints);
  json values = json::array();
  for (std::size_t i = 0; i < n; i += step) {
    values.push_back({{"t", s.time_s[i]}, {"I", s.current_A[i]}, {"series", "raw"}});
    if (p.kept_mask[i])
      values.push_back({{"t", s.time_s[i]}, {"I", p.cleaned_A[i]}, {"series", "cleaned (kept)"}});
  }
  json rejected = json::array();
  if (p.stationarity)
    for (const auto& seg : p.stationarity->segments)
      if (!seg.kept)
        rejected.push_back({{"t0", s.time_s[seg.begin]}, {"t1", s.time_s[seg.end - 1]}});
  json layers = json::array();
  layers.push_back(
      {{"data", {{"values", rejected}}},
       {"mark", {{"type", "rect"}, {"color", "#f4c7c3"}, {"opacity", 0.6}}},
       {"encoding",
        {{"x", {{"field", "t0"}, {"type", "quantitative"}}}, {"x2", {{"field", "t1"}}}}}});
  layers.push_back({{"data", {{"values", values}}},
                    {"mark", {{"type", "line"}, {"strokeWidth", 1}}},
                    {"encoding",
                     {{"x", {{"field", "t"}, {"type", "quantitative"}, {"title", "time (s)"}}},
                      {"y",
                       {{"field", "I"},
                        {"type", "quantitative"},
                        {"title", "current (A)"},
                        {"scale", {{"zero", false}}}}},
                      {"color", {{"field", "series"}, {"type", "nominal"}, {"title", ""}}}}}});
  json spec = {{"width", 700}, {"height", 260}, {"layer", layers}};
  return {fmt::format("{}: raw and cleaned series", name), spec,
          fmt::format("Every {}. sample drawn. Shaded: rejected segments (not used).", step)};
}

Table segment_table(const maglev::StationarityResult& st) {
  Table t;
  t.title = "Segments";
  t.columns = {"segment", "samples", "mean (A)", "z (mean)", "Q (autocov.)", "kept"};
  t.numeric = {true, false, true, true, true, false};
  for (std::size_t i = 0; i < st.segments.size(); ++i) {
    const auto& s = st.segments[i];
    t.rows.push_back({std::to_string(i), fmt::format("{}…{}", s.begin, s.end - 1),
                      fmt::format("{:.9g}", s.mean), fmt::format("{:.2f}", s.z_mean),
                      fmt::format("{:.1f}", s.q_autocovariance), s.kept ? "yes" : "REJECTED"});
  }
  t.note = fmt::format("Each test at α = {:.4g} per segment (family-wise α over the position).",
                       st.segment_alpha);
  return t;
}

// The result section: α1 and N_G, the estimators side by side, notes and warnings.
Section reduce_result_section(const maglev::ReduceResult& r) {
  Section res{"result", "Result", {}, 2};
  res.blocks.push_back(Highlight{
      "α1 (processed)",
      fmt::format("{} ± {:.3f}\"",
                  format_dms(Angle::radians(r.processed.alpha1_rad.value), {3, true, true}),
                  units::rad_to_arcsec(r.processed.alpha1_rad.sigma)),
      "spin axis east of north at position 1", false});
  res.blocks.push_back(Highlight{
      "gyro north N_G",
      fmt::format(
          "{} ± {:.3f}\"",
          format_direction_dms(Angle::radians(r.processed.north_rad.value), {3, true, false}),
          units::rad_to_arcsec(r.processed.north_rad.sigma)),
      "N_G = r1 − α1", false});
  KeyValueList kv{"Estimators side by side", {}};
  kv.items.push_back({"processed (cleaned kept means)", solution_text(r.processed)});
  kv.items.push_back({"plain means of all samples", solution_text(r.plain)});
  if (r.median) kv.items.push_back({"medians of kept samples", solution_text(*r.median)});
  if (r.huber) kv.items.push_back({"Huber means of kept samples", solution_text(*r.huber)});
  kv.items.push_back({"processed − plain",
                      fmt::format("{:+.3f}\"", units::rad_to_arcsec(r.processed.alpha1_rad.value -
                                                                    r.plain.alpha1_rad.value))});
  res.blocks.push_back(kv);
  if (r.drift) {
    const auto& d = *r.drift;
    KeyValueList dk{"Drift on the common clock", {}};
    dk.items.push_back({"model, blocks", fmt::format("{}, {}", maglev::to_string(d.model), d.sequence)});
    dk.items.push_back({"rate at t_ref", fmt::format("{:+.4e} ± {:.3e} A/s (z = {:.2f}, {})",
                                                     d.rate_A_per_s.value, d.rate_A_per_s.sigma, d.z,
                                                     d.significant ? "significant" : "not significant")});
    if (d.curvature_A_per_s2)
      dk.items.push_back({"curvature", fmt::format("{:+.4e} ± {:.3e} A/s²", d.curvature_A_per_s2->value,
                                                   d.curvature_A_per_s2->sigma)});
    dk.items.push_back({"α1 corrected by", fmt::format("{:+.3f}\"", units::rad_to_arcsec(d.alpha1_correction_rad))});
    dk.items.push_back({"σ(α1) inflation by the drift",
                        fmt::format("×{:.2f} ({})", d.sigma_inflation,
                                    d.separable ? "separable" : "cannot be well separated")});
    for (const auto& b : d.blocks)
      dk.items.push_back({fmt::format("block (position {})", b.position),
                          fmt::format("{:.3f} … {:.3f} s, {} samples", b.begin_s, b.end_s, b.end - b.begin)});
    res.blocks.push_back(dk);
  }
  if (!r.notes.empty()) res.blocks.push_back(Notes{"Notes", r.notes, false});
  if (!r.warnings.empty()) res.blocks.push_back(Notes{"Warnings", r.warnings, true});
  return res;
}

// A position's section: its statistics, the raw and cleaned series, the segments.
Section position_section(int k, const maglev::PositionResult& p) {
  const std::string name = fmt::format("Position {}", k);
  Section sec{fmt::format("position{}", k), name, {}, 2};
  sec.blocks.push_back(KeyValueList{
      "Statistics",
      {{"samples (kept)", fmt::format("{} ({})", p.samples, p.kept_samples)},
       {"mean of all samples", fmt::format("{:.10g} ± {:.3g} A", p.raw.mean, p.raw.sigma)},
       {"mean cleaned, kept",
        fmt::format("{:.10g} ± {:.3g} A (n_eff {:.0f})", p.cleaned_mean_A.value,
                    p.cleaned_mean_A.sigma, p.kept.n_eff)},
       {"variance raw / cleaned kept",
        fmt::format("{:.3e} / {:.3e} A²", p.variance_raw_A2, p.variance_cleaned_A2)}}});
  sec.blocks.push_back(series_plot(name.c_str(), p));
  if (p.stationarity) sec.blocks.push_back(segment_table(*p.stationarity));
  return sec;
}

// The calibration's lines, intersection and K.
KeyValueList calibration_lines(const maglev::CalibrationResult& r) {
  return KeyValueList{
      "Curves I = k·sin(α − α*) + I* (joint fit)",
      {{"position 1",
        fmt::format("k = {:.9g} ± {:.3g} A/rad, c = {:.9g} ± {:.3g} A",
                    r.position1.slope_A_per_rad.value, r.position1.slope_A_per_rad.sigma,
                    r.position1.intercept_A.value, r.position1.intercept_A.sigma)},
       {"position 2",
        fmt::format("k = {:.9g} ± {:.3g} A/rad, c = {:.9g} ± {:.3g} A",
                    r.position2.slope_A_per_rad.value, r.position2.slope_A_per_rad.sigma,
                    r.position2.intercept_A.value, r.position2.intercept_A.sigma)},
       {"trend deviation k1 + k2",
        fmt::format("{:.6g} ± {:.3g} A/rad ({})", r.trend_deviation_A_per_rad.value,
                    r.trend_deviation_A_per_rad.sigma,
                    r.trend_significant ? "significant" : "not significant")},
       {"model check σ̂0",
        fmt::format("{:.2f} (dof {}, {})", r.fit_test.sigma0, r.fit_test.dof,
                    r.fit_test.rejected ? "REJECTED" : "passed")},
       {"instrument constant α* (best set-up azimuth)",
        fmt::format("{} ± {:.3f}\"",
                    format_dms(Angle::radians(r.best_azimuth_rad.value), {3, true, true}),
                    units::rad_to_arcsec(r.best_azimuth_rad.sigma))},
       {"constant deviation I*", fmt::format("{:.6e} ± {:.3g} A", r.constant_deviation_A.value,
                                             r.constant_deviation_A.sigma)},
       {"K from the slopes", fmt::format("{:.6f} ± {:.4f} A·s/rad", r.scale_A_s_per_rad.value,
                                         r.scale_A_s_per_rad.sigma)}}};
}

// The position means against the set-up azimuth, and the residuals of the line fits.
std::pair<Plot, Plot> calibration_plots(const maglev::CalibrationResult& r) {
  json values = json::array();
  for (std::size_t i = 0; i < r.setups.size(); ++i) {
    const auto& s = r.setups[i];
    const double a = units::rad_to_deg(s.azimuth_rad);
    values.push_back(
        {{"a", a}, {"I", s.mean1_A.value}, {"p", "position 1"}, {"v", r.position1.residuals_A[i]}});
    values.push_back(
        {{"a", a}, {"I", s.mean2_A.value}, {"p", "position 2"}, {"v", r.position2.residuals_A[i]}});
  }
  json enc = {{"x", {{"field", "a"}, {"type", "quantitative"}, {"title", "set-up azimuth (deg)"}}},
              {"color", {{"field", "p"}, {"type", "nominal"}, {"title", ""}}}};
  json means = {
      {"width", 600},
      {"height", 260},
      {"data", {{"values", values}}},
      {"layer",
       json::array(
           {{{"mark", "point"},
             {"encoding",
              {{"x", enc["x"]},
               {"color", enc["color"]},
               {"y", {{"field", "I"}, {"type", "quantitative"}, {"title", "mean current (A)"}}}}}},
            {{"mark", "line"},
             {"encoding",
              {{"x", enc["x"]},
               {"color", enc["color"]},
               {"y", {{"field", "I"}, {"type", "quantitative"}}}}}}})}};
  Plot means_plot{"Position means against the set-up azimuth", means,
                  "Points: the means; lines join them."};
  json resid = {
      {"width", 600},
      {"height", 200},
      {"data", {{"values", values}}},
      {"mark", "point"},
      {"encoding",
       {{"x", enc["x"]},
        {"color", enc["color"]},
        {"y",
         {{"field", "v"}, {"type", "quantitative"}, {"title", "residual fit − observed (A)"}}}}}};
  return {means_plot, Plot{"Residuals of the line fits", resid, ""}};
}


// A report on the input `source` (subtitle and first header line) with the rest of its header.
Document maglev_document(std::string title, const std::string& source, std::vector<KeyValue> header) {
  Document doc;
  doc.title = std::move(title);
  doc.subtitle = source;
  doc.footer = report_generator();
  doc.header = {{"input", source}};
  doc.header.insert(doc.header.end(), header.begin(), header.end());
  return doc;
}
}  // namespace

Document maglev_reduce_document(const maglev::ReduceResult& r) {
  Document doc = maglev_document(
      "Maglev gyro two-position determination", r.source,
      {{"scale K", fmt::format("{:.6f} ± {:.4f} A·s/rad", r.scale_A_s_per_rad.value,
                               r.scale_A_s_per_rad.sigma)},
       {"latitude", format_dms(Angle::radians(r.latitude_rad))},
       {"directive amplitude A", fmt::format("{:.9g} A", r.amplitude_A.value)},
       {"processing",
        r.options.process ? "stationarity tests, wavelet denoising" : "none (plain means)"}});
  doc.sections.push_back(reduce_result_section(r));
  doc.sections.push_back(position_section(1, r.position1));
  doc.sections.push_back(position_section(2, r.position2));
  return doc;
}

Document maglev_calibration_document(const maglev::CalibrationResult& r) {
  Document doc = maglev_document("Maglev gyro multi-angle calibration", r.source,
                                 {{"set-ups", std::to_string(r.setups.size())},
                                  {"latitude", format_dms(Angle::radians(r.latitude_rad))}});
  Section res{"calibration", "Result", {}, 2};
  res.blocks.push_back(calibration_lines(r));
  if (!r.warnings.empty()) res.blocks.push_back(Notes{"Warnings", r.warnings, true});
  auto [means, residuals] = calibration_plots(r);
  res.blocks.push_back(std::move(means));
  res.blocks.push_back(std::move(residuals));
  doc.sections.push_back(res);
  return doc;
}

}  // namespace meridian::report
