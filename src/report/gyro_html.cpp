#include "meridian/report/gyro_html.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "format.hpp"
#include "meridian/core/angle.hpp"
#include "meridian/core/units.hpp"
#include "meridian/geodesy/grid.hpp"

#ifndef MERIDIAN_VERSION
#define MERIDIAN_VERSION "unknown"
#endif

namespace meridian::report {
namespace {

using nlohmann::json;
using namespace fmtx;
constexpr double kArcsec = units::kArcsecond;
constexpr double kDeg = units::kDegree;
constexpr int kPlotWidth = 620;

std::string footer() { return std::string("meridian ") + MERIDIAN_VERSION; }

json axis(const char* field, const char* title, bool zero = false) {
  return {{"field", field}, {"type", "quantitative"}, {"title", title}, {"scale", {{"zero", zero}}}};
}

// An axis of whole-number indices (reversal 1, 2, …).
json index_axis(const char* field, const char* title) {
  json a = axis(field, title);
  a["axis"] = {{"tickMinStep", 1}, {"format", "d"}};
  return a;
}

// ---------------------------------------------------------------- plots

// Turning-point times of the fitted oscillation for reversal readings given
// without times: successive turning points on the reading's side.
std::vector<double> reversal_times(const gyro::DeterminationInput& in, const gyro::UnifiedFitResult& f) {
  const auto& o = in.nontracking;
  if (!o.reversal_times_s.empty()) return o.reversal_times_s;
  double t_first = std::numeric_limits<double>::infinity();
  for (const auto& c : o.crossings)
    if (!c.times_s.empty()) t_first = std::min(t_first, c.times_s.front());
  if (!std::isfinite(t_first)) t_first = f.t0_s.value;
  const double T = f.period_s.value, t0 = f.t0_s.value;
  // Turning point k at t0 + T/4 + k·T/2: east (+) for even k. Start at the
  // first turning point after t_first − T/4 (readings are taken while timing).
  long k = static_cast<long>(std::ceil((t_first - T / 4 - t0 - T / 4) / (T / 2)));
  std::vector<double> out;
  for (double a : o.reversals_div) {
    const bool east = a > f.beta_div.value;
    while (((k % 2 + 2) % 2 == 0) != east) ++k;
    out.push_back(t0 + T / 4 + static_cast<double>(k) * T / 2);
    ++k;
  }
  return out;
}

Plot oscillation_plot(const gyro::DeterminationInput& in, const gyro::UnifiedFitResult* fit,
                      double beta_div) {
  const auto& o = in.nontracking;
  json obs = json::array();
  double tmin = std::numeric_limits<double>::infinity(), tmax = -tmin;
  for (std::size_t i = 0; i < o.crossings.size(); ++i) {
    const auto& c = o.crossings[i];
    for (std::size_t j = 0; j < c.times_s.size(); ++j) {
      obs.push_back({{"t", c.times_s[j]}, {"a", c.level_div}, {"kind", "crossing"},
                     {"label", fmt::format("crossings[{}].times_s[{}]", i, j)}});
      tmin = std::min(tmin, c.times_s[j]);
      tmax = std::max(tmax, c.times_s[j]);
    }
  }
  std::string caption = "Points: timed crossings of graduations and reversal readings. ";
  std::vector<double> rt;
  if (fit) rt = reversal_times(in, *fit);
  else if (!o.reversal_times_s.empty()) rt = o.reversal_times_s;
  for (std::size_t j = 0; j < o.reversals_div.size() && j < rt.size(); ++j) {
    obs.push_back({{"t", rt[j]}, {"a", o.reversals_div[j]}, {"kind", "reversal"},
                   {"label", fmt::format("reversals_div[{}]", j)}});
    tmin = std::min(tmin, rt[j]);
    tmax = std::max(tmax, rt[j]);
  }
  if (rt.empty() && !o.reversals_div.empty()) caption += "Reversal readings without times are not drawn. ";
  if (fit && o.reversal_times_s.empty() && !o.reversals_div.empty())
    caption += "Reversal readings were not timed: they are drawn at the fitted turning points. ";
  json layers = json::array();
  if (fit) {
    const double T = fit->period_s.value, t0 = fit->t0_s.value, B = fit->amplitude_div.value;
    const double k = fit->damping_per_s.value, b = fit->beta_div.value;
    const double lo = tmin - T / 8, hi = tmax + T / 8;
    json curve = json::array();
    for (int i = 0; i <= 400; ++i) {
      const double t = lo + (hi - lo) * i / 400.0;
      curve.push_back({{"t", t}, {"a", b + B * std::exp(-k * (t - t0)) * std::sin(2 * units::kPi * (t - t0) / T)}});
    }
    layers.push_back({{"data", {{"values", curve}}},
                      {"mark", {{"type", "line"}, {"color", "#0b5cad"}, {"strokeWidth", 1.5}}},
                      {"encoding", {{"x", axis("t", "time (s)")}, {"y", axis("a", "scale reading (div, east +)")}}}});
    caption += "Line: the unified least-squares fit of (N1). ";
  } else {
    caption += "No fitted model for this method (closed form); the dashed line is beta. ";
  }
  layers.push_back({{"data", {{"values", json::array({{{"beta", beta_div}}})}}},
                    {"mark", {{"type", "rule"}, {"strokeDash", {4, 4}}, {"color", "#888888"}}},
                    {"encoding", {{"y", {{"field", "beta"}, {"type", "quantitative"}}}}}});
  layers.push_back({{"data", {{"values", obs}}},
                    {"mark", {{"type", "point"}, {"filled", true}, {"size", 70}}},
                    {"encoding",
                     {{"x", axis("t", "time (s)")},
                      {"y", axis("a", "scale reading (div, east +)")},
                      {"color", {{"field", "kind"}, {"type", "nominal"}, {"title", "observation"}}},
                      {"shape", {{"field", "kind"}, {"type", "nominal"}}},
                      {"tooltip", json::array({{{"field", "label"}}, {{"field", "t"}}, {{"field", "a"}}})}}}});
  caption += fmt::format("Dashed: the equilibrium reading beta = {:.4f} div.", beta_div);
  return {"Oscillation: observations and model",
          {{"width", kPlotWidth}, {"height", 240}, {"layer", layers}},
          caption};
}

Plot fit_residual_plot(const gyro::UnifiedFitResult& f) {
  json v = json::array();
  int i = 0;
  for (const auto& r : f.residuals) {
    const bool time = r.kind == gyro::UnifiedFitResidual::Kind::CrossingTime;
    v.push_back({{"i", ++i},
                 {"w", std::isfinite(r.standardized) ? json(r.standardized) : json(0.0)},
                 {"v", r.residual},
                 {"kind", time ? "crossing time (s)" : "reversal reading (div)"},
                 {"label", time ? fmt::format("crossings[{}].times_s[{}]", r.group, r.index)
                                : fmt::format("reversals_div[{}]", r.index)}});
  }
  json rules = json::array({{{"y", 0}}, {{"y", 3}}, {{"y", -3}}});
  json spec = {{"width", kPlotWidth},
               {"height", 160},
               {"layer",
                json::array({{{"data", {{"values", rules}}},
                              {"mark", {{"type", "rule"}, {"color", "#bbbbbb"}, {"strokeDash", {3, 3}}}},
                              {"encoding", {{"y", {{"field", "y"}, {"type", "quantitative"}}}}}},
                             {{"data", {{"values", v}}},
                              {"mark", {{"type", "point"}, {"filled", true}, {"size", 60}}},
                              {"encoding",
                               {{"x", index_axis("i", "observation")},
                                {"y", axis("w", "standardised residual", true)},
                                {"color", {{"field", "kind"}, {"type", "nominal"}, {"title", "observation"}}},
                                {"tooltip", json::array({{{"field", "label"}}, {{"field", "v"}, {"title", "residual"}}, {{"field", "w"}}})}}}}})}};
  return {"Residuals of the unified fit", spec,
          fmt::format("Standardised residuals v/sigma_v (v = fitted - observed); dashed lines at 0 and +-3. "
                      "sigma0 = {}, {} degrees of freedom.",
                      num(f.sigma0, 3), f.dof)};
}

// Every method's N_G as an offset from the reported one, with ±σ bars.
Plot methods_plot(const gyro::DeterminationResult& r) {
  json v = json::array();
  for (const auto& m : r.all) {
    const double d = wrap_signed_rad(m.north.north_rad - r.primary.north.north_rad) / kArcsec;
    const double s = std::isfinite(m.north.sigma_rad) ? m.north.sigma_rad / kArcsec : 0.0;
    v.push_back({{"method", m.method}, {"d", d}, {"lo", d - s}, {"hi", d + s}});
  }
  json spec = {{"width", kPlotWidth},
               {"height", 26 * static_cast<int>(r.all.size()) + 20},
               {"layer",
                json::array({{{"data", {{"values", v}}},
                              {"mark", {{"type", "rule"}, {"color", "#0b5cad"}}},
                              {"encoding", {{"y", {{"field", "method"}, {"type", "nominal"}, {"sort", nullptr}, {"title", nullptr}}},
                                            {"x", axis("lo", "N_G minus the reported result (arcsec)")},
                                            {"x2", {{"field", "hi"}}}}}},
                             {{"data", {{"values", v}}},
                              {"mark", {{"type", "point"}, {"filled", true}, {"size", 80}, {"color", "#0b5cad"}}},
                              {"encoding", {{"y", {{"field", "method"}, {"type", "nominal"}, {"sort", nullptr}}},
                                            {"x", {{"field", "d"}, {"type", "quantitative"}}},
                                            {"tooltip", json::array({{{"field", "method"}}, {{"field", "d"}, {"title", "offset (arcsec)"}}})}}}}})}};
  return {"Every method on the same data", spec,
          fmt::format("Bars: +-1 sigma. Reported result: {}.", r.primary.method)};
}

Plot tracking_plot(const gyro::DeterminationInput& in, const gyro::ReversalResult& fit) {
  const auto r = gyro::unwrap_circle_readings(in.tracking.reversals_rad);
  const double m = fit.centre.value;
  json v = json::array();
  for (std::size_t i = 0; i < r.size(); ++i) {
    const double obs = wrap_signed_rad(r[i] - m) / kArcsec;
    const double res = i < fit.residuals.size() ? fit.residuals[i] / kArcsec : 0.0;
    v.push_back({{"i", static_cast<int>(i + 1)}, {"obs", obs}, {"fitted", obs + res}, {"v", res}});
  }
  json spec = {{"width", kPlotWidth},
               {"height", 220},
               {"layer",
                json::array({{{"data", {{"values", json::array({{{"y", 0}}})}}},
                              {"mark", {{"type", "rule"}, {"strokeDash", {4, 4}}, {"color", "#888888"}}},
                              {"encoding", {{"y", {{"field", "y"}, {"type", "quantitative"}}}}}},
                             {{"data", {{"values", v}}},
                              {"mark", {{"type", "line"}, {"point", true}, {"color", "#0b5cad"}}},
                              {"encoding", {{"x", index_axis("i", "reversal")}, {"y", axis("fitted", "reading minus M (arcsec)")}}}},
                             {{"data", {{"values", v}}},
                              {"mark", {{"type", "point"}, {"filled", true}, {"size", 70}, {"color", "#d9480f"}, {"shape", "diamond"}}},
                              {"encoding", {{"x", {{"field", "i"}, {"type", "quantitative"}}},
                                            {"y", {{"field", "obs"}, {"type", "quantitative"}}},
                                            {"tooltip", json::array({{{"field", "i"}}, {{"field", "obs"}, {"title", "observed"}}, {{"field", "v"}, {"title", "residual"}}})}}}}})}};
  return {"Tracking: reversal readings and model", spec,
          fmt::format("Diamonds: circle readings at the reversals relative to the centre M ({}); line: the "
                      "{} model (fitted = observed + residual). Dashed: M.",
                      dir(m, 2), gyro::to_string(fit.method))};
}

Plot tracking_residual_plot(const gyro::ReversalResult& fit) {
  json v = json::array();
  for (std::size_t i = 0; i < fit.residuals.size(); ++i)
    v.push_back({{"i", static_cast<int>(i + 1)}, {"v", fit.residuals[i] / kArcsec}});
  json spec = {{"width", kPlotWidth},
               {"height", 150},
               {"layer",
                json::array({{{"data", {{"values", json::array({{{"y", 0}}})}}},
                              {"mark", {{"type", "rule"}, {"color", "#bbbbbb"}}},
                              {"encoding", {{"y", {{"field", "y"}, {"type", "quantitative"}}}}}},
                             {{"data", {{"values", v}}},
                              {"mark", {{"type", "bar"}, {"color", "#d9480f"}, {"size", 14}}},
                              {"encoding", {{"x", index_axis("i", "reversal")},
                                            {"y", axis("v", "residual v (arcsec)", true)},
                                            {"tooltip", json::array({{{"field", "i"}}, {{"field", "v"}}})}}}}})}};
  return {"Tracking: residuals", spec,
          fmt::format("v = fitted - observed for the {} fit; sigma0 = {} arcsec with {} degrees of freedom.",
                      gyro::to_string(fit.method), num(fit.sigma0 / kArcsec, 2), fit.dof)};
}

Plot zero_position_plot(const gyro::DeterminationInput& in, const gyro::ZeroPositionSummary& z) {
  json v = json::array(), centres = json::array();
  auto add = [&](const char* run, const std::optional<gyro::ZeroPositionRun>& r,
                 const std::optional<gyro::ZeroPositionEstimate>& e) {
    if (!r || !e) return;
    for (std::size_t i = 0; i < r->reversals_div.size(); ++i)
      v.push_back({{"run", run}, {"i", static_cast<int>(i + 1)}, {"a", r->reversals_div[i]}});
    centres.push_back({{"run", run}, {"c", e->fit.centre.value}});
  };
  add("before", in.zero_before, z.before);
  add("after", in.zero_after, z.after);
  json spec = {{"width", kPlotWidth},
               {"height", 180},
               {"layer",
                json::array({{{"data", {{"values", v}}},
                              {"mark", {{"type", "line"}, {"point", true}}},
                              {"encoding", {{"x", index_axis("i", "reversal")},
                                            {"y", axis("a", "scale reading (div)")},
                                            {"color", {{"field", "run"}, {"type", "nominal"}, {"title", "motor-off run"}}}}}},
                             {{"data", {{"values", centres}}},
                              {"mark", {{"type", "rule"}, {"strokeDash", {4, 4}}}},
                              {"encoding", {{"y", {{"field", "c"}, {"type", "quantitative"}}},
                                            {"color", {{"field", "run"}, {"type", "nominal"}}}}}}})}};
  return {"Zero position (motor off)", spec,
          fmt::format("Free oscillation reversal readings; dashed: the estimated centres. alpha_p used = {} div "
                      "(sigma {}).",
                      num(z.mean_div.value, 3), num(z.mean_div.sigma, 3))};
}

// Values with ±σ bars about their mean (gyro azimuths, instrument constants).
Plot spread_plot(const std::string& title, const std::vector<std::string>& labels,
                 const std::vector<gyro::Uncertain>& values, double mean, double mean_sigma,
                 const std::string& x_title, const std::string& caption) {
  json v = json::array();
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double d = wrap_signed_rad(values[i].value - mean) / kArcsec;
    const double s = values[i].sigma / kArcsec;
    v.push_back({{"label", labels[i]}, {"d", d}, {"lo", d - s}, {"hi", d + s}});
  }
  const double ms = mean_sigma / kArcsec;
  json band = json::array({{{"lo", -ms}, {"hi", ms}}});
  json spec = {{"width", kPlotWidth},
               {"height", 28 * static_cast<int>(values.size()) + 20},
               {"layer",
                json::array({{{"data", {{"values", band}}},
                              {"mark", {{"type", "rect"}, {"color", "#dbe7f5"}}},
                              {"encoding", {{"x", axis("lo", x_title.c_str())}, {"x2", {{"field", "hi"}}}}}},
                             {{"data", {{"values", v}}},
                              {"mark", {{"type", "rule"}, {"color", "#0b5cad"}}},
                              {"encoding", {{"y", {{"field", "label"}, {"type", "nominal"}, {"sort", nullptr}, {"title", nullptr}}},
                                            {"x", {{"field", "lo"}, {"type", "quantitative"}}},
                                            {"x2", {{"field", "hi"}}}}}},
                             {{"data", {{"values", v}}},
                              {"mark", {{"type", "point"}, {"filled", true}, {"size", 80}, {"color", "#0b5cad"}}},
                              {"encoding", {{"y", {{"field", "label"}, {"type", "nominal"}, {"sort", nullptr}}},
                                            {"x", {{"field", "d"}, {"type", "quantitative"}}},
                                            {"tooltip", json::array({{{"field", "label"}}, {{"field", "d"}, {"title", "offset (arcsec)"}}})}}}}})}};
  return {title, spec, caption};
}

// ---------------------------------------------------------------- tables

Table methods_table(const gyro::DeterminationResult& r) {
  const std::vector<gyro::MethodResult>& ms = r.method == "all" ? r.all : std::vector<gyro::MethodResult>{r.primary};
  Table t;
  t.title = r.method == "all" ? "Every applicable method" : "Result";
  if (r.mode == gyro::Mode::NonTracking) {
    t.columns = {"method", "beta (div)", "sigma beta (div)", "delta N", "N_G", "sigma N_G", "approximation error", "warnings"};
    t.numeric = {false, true, true, true, true, true, true, false};
    for (const auto& m : ms) {
      std::string w;
      if (m.beta)
        for (const auto& x : m.beta->warnings) w += (w.empty() ? "" : "; ") + x;
      t.rows.push_back({m.method + (m.method == r.primary.method && r.method == "all" ? " (reported)" : ""),
                        m.beta ? num(m.beta->beta_div.value, 5) : "",
                        m.beta ? num(m.beta->beta_div.sigma, 5) : "", sec(m.north.delta_n_rad, 3),
                        dir(m.north.north_rad, 2), sig(m.north.sigma_rad, 2),
                        m.approximation_error_rad != 0.0 ? sec(m.approximation_error_rad, 3) : "exact", w});
    }
  } else {
    t.columns = {"method", "N_G", "sigma N_G", "dof", "sigma0 (arcsec)", "sigma basis"};
    t.numeric = {false, true, true, true, true, false};
    for (const auto& m : ms) {
      const auto& f = *m.reversal;
      t.rows.push_back({m.method + (m.method == r.primary.method && r.method == "all" ? " (reported)" : ""),
                        dir(m.north.north_rad, 2), sig(m.north.sigma_rad, 2), std::to_string(f.dof),
                        num(f.sigma0 / kArcsec, 2),
                        std::isfinite(f.centre.sigma) ? (f.sigma_is_aposteriori ? "a posteriori" : "a priori") : "n/a"});
    }
  }
  return t;
}

Table fit_table(const gyro::UnifiedFitResult& f) {
  Table t;
  t.title = "Unified least-squares fit of (N1)";
  t.columns = {"parameter", "estimate", "sigma", "unit"};
  t.numeric = {false, true, true, false};
  t.rows = {{"beta (equilibrium reading)", num(f.beta_div.value, 5), num(f.beta_div.sigma, 5), "div"},
            {"B (amplitude at t0)", num(f.amplitude_div.value, 4), num(f.amplitude_div.sigma, 4), "div"},
            {"t0 (eastward passage of beta)", num(f.t0_s.value, 3), num(f.t0_s.sigma, 3), "s"},
            {"T_B (period)", num(f.period_s.value, 3), num(f.period_s.sigma, 3), "s"},
            {"k (damping)", fmt::format("{:.3g}", f.damping_per_s.value), fmt::format("{:.3g}", f.damping_per_s.sigma), "1/s"}};
  t.note = fmt::format("sigma are a priori (from the stated observation sigma); sigma0 = {}, {} degrees of freedom, "
                       "{} iterations.",
                       num(f.sigma0, 3), f.dof, f.iterations);
  return t;
}

// All blocks describing one determination.
std::vector<Block> determination_blocks(const gyro::DeterminationInput& in, const gyro::DeterminationResult& r) {
  std::vector<Block> b;
  std::vector<KeyValue> kv{{"mode", gyro::to_string(r.mode)}, {"method requested", r.method},
                           {"reported method", r.primary.method},
                           {"N_G (gyro north as a circle reading)", dir(r.primary.north.north_rad, 2)},
                           {"sigma N_G", sig(r.primary.north.sigma_rad, 2)}};
  if (r.mode == gyro::Mode::NonTracking) {
    kv.push_back({"clamp reading N'", dir(in.clamp_reading_rad, 1)});
    kv.push_back({"delta N = N_G - N'", sec(r.primary.north.delta_n_rad, 3)});
  }
  if (r.zero_position_used)
    kv.push_back({"zero position alpha_p / correction -lambda tau alpha_p",
                  fmt::format("{} div (sigma {}) / {}", num(r.zero_position_used->value, 3),
                              num(r.zero_position_used->sigma, 3), sec(r.primary.north.zero_correction_rad, 2))});
  else
    kv.push_back({"zero position", "not given: no zero-position correction applied"});
  if (in.target_reading_rad) kv.push_back({"circle reading to the target", dir(in.target_reading_rad->value, 1)});
  b.push_back(KeyValueList{"", kv});
  b.push_back(methods_table(r));
  if (r.mode == gyro::Mode::NonTracking) {
    const gyro::UnifiedFitResult* fit = r.primary.fit ? &*r.primary.fit : nullptr;
    if (!fit)
      for (const auto& m : r.all)
        if (m.fit) fit = &*m.fit;
    b.push_back(oscillation_plot(in, fit, r.primary.beta ? r.primary.beta->beta_div.value : 0.0));
    if (fit) {
      b.push_back(fit_table(*fit));
      b.push_back(fit_residual_plot(*fit));
    }
  } else if (r.primary.reversal) {
    b.push_back(tracking_plot(in, *r.primary.reversal));
    if (r.primary.reversal->dof > 0) b.push_back(tracking_residual_plot(*r.primary.reversal));
  }
  if (r.method == "all" && r.all.size() > 1) b.push_back(methods_plot(r));
  if (r.zero_position) b.push_back(zero_position_plot(in, *r.zero_position));
  b.push_back(Notes{"Warnings", r.warnings, true});
  return b;
}

std::vector<KeyValue> instrument_header(const gyro::InstrumentSpec& s, const gyro::Instrument& at_station) {
  std::vector<KeyValue> h;
  if (!s.name.empty()) h.push_back({"instrument", s.name});
  h.push_back({"scale value tau", fmt::format("{:.2f}\"/div", s.scale_value_rad / kArcsec)});
  if (s.torsion_ratio)
    h.push_back({"torsion ratio lambda (given)",
                 fmt::format("{:.5f} (sigma {:.5f}){}", s.torsion_ratio->value, s.torsion_ratio->sigma,
                             s.constants_latitude_rad ? fmt::format(" at latitude {:.4f} deg", *s.constants_latitude_rad / kDeg) : "")});
  h.push_back({"torsion ratio lambda at the station",
               fmt::format("{:.5f} (sigma {:.5f})", at_station.torsion_ratio.value, at_station.torsion_ratio.sigma)});
  if (at_station.transit_factor_rad_per_div_s)
    h.push_back({"calibrated transit factor c",
                 fmt::format("{:.4f}\"/(div s)", at_station.transit_factor_rad_per_div_s->value / kArcsec)});
  h.push_back({"observation sigma", fmt::format("time {} s, scale reading {} div", s.sigma_time_s, s.sigma_reading_div)});
  h.push_back({"accuracy class", fmt::format("{}\"", s.accuracy_class_arcsec)});
  return h;
}

std::string point_text(const gyro::PointResult& p) {
  return fmt::format("{}: latitude {}, longitude {}; x {:.3f} m, y {:.3f} m; convergence {}", p.name,
                     format_dms(Angle::radians(p.lat_rad), {3, true, false}),
                     format_dms(Angle::radians(p.lon_rad), {3, true, false}), p.grid.x_north_m, p.grid.y_east_m,
                     dms(p.grid.convergence_rad, 2));
}

std::string label_of(const gyro::DeterminationResult& d, std::size_t i) {
  return d.label.empty() ? fmt::format("#{} ({})", i + 1, d.primary.method) : d.label;
}

}  // namespace

Document gyro_reduce_document(const std::string& file, const gyro::ResolvedInstrument& instrument,
                              double latitude_rad, const std::vector<gyro::DeterminationInput>& inputs,
                              const std::vector<gyro::DeterminationResult>& results) {
  Document doc;
  doc.title = "Gyro-theodolite determinations";
  doc.subtitle = file;
  doc.footer = footer();
  doc.header.push_back({"input file", file});
  doc.header.push_back({"station latitude", format_dms(Angle::radians(latitude_rad), {2, true, false})});
  gyro::InstrumentSpec spec_view;  // instrument constants as resolved
  spec_view.scale_value_rad = instrument.instrument.scale_value_rad;
  spec_view.sigma_time_s = instrument.instrument.sigma_time_s;
  spec_view.sigma_reading_div = instrument.instrument.sigma_reading_div;
  for (auto& kv : instrument_header(spec_view, instrument.instrument))
    if (kv.key != "accuracy class") doc.header.push_back(kv);
  Section summary{"summary", "Summary", {}, 2};
  Table t;
  t.title = "N_G of every determination";
  t.columns = {"#", "label", "mode", "method", "N_G", "sigma", "delta N"};
  t.numeric = {true, false, false, false, true, true, true};
  for (std::size_t i = 0; i < results.size(); ++i) {
    const auto& r = results[i];
    t.rows.push_back({std::to_string(i + 1), r.label, gyro::to_string(r.mode), r.primary.method,
                      dir(r.primary.north.north_rad, 2), sig(r.primary.north.sigma_rad, 2),
                      sec(r.primary.north.delta_n_rad, 3)});
  }
  summary.blocks.push_back(t);
  summary.blocks.push_back(Notes{"Notes", instrument.notes, false});
  doc.sections.push_back(summary);
  for (std::size_t i = 0; i < results.size(); ++i) {
    Section s{fmt::format("determination-{}", i + 1),
              fmt::format("Determination {}{}", i + 1, results[i].label.empty() ? "" : ": " + results[i].label),
              determination_blocks(inputs[i], results[i]), 2};
    doc.sections.push_back(s);
  }
  return doc;
}

Document gyro_campaign_document(const std::string& file, const gyro::CampaignInput& in,
                                const gyro::CampaignResult& r) {
  Document doc;
  doc.title = "Gyro orientation: " + (r.name.empty() ? std::string("campaign") : r.name);
  doc.subtitle = file;
  doc.footer = footer();
  doc.header.push_back({"input file", file});
  for (auto& kv : instrument_header(in.instrument, r.instrument_station.instrument)) doc.header.push_back(kv);
  doc.header.push_back({"grid", geodesy::describe(in.grid)});
  doc.header.push_back({"station", point_text(r.station)});
  if (r.target) doc.header.push_back({"target", point_text(*r.target)});
  if (r.known_station) doc.header.push_back({"known station", point_text(*r.known_station)});

  const auto& c = r.chain;
  const std::string line_name = r.station.name + (r.target ? " to " + r.target->name : "");
  Section result{"result", "Result", {}, 2};
  result.blocks.push_back(Highlight{"Grid azimuth " + line_name,
                                    dir(c.grid_azimuth_rad.value, 1) + "  \u00b1 " + sig(c.grid_azimuth_rad.sigma, 1),
                                    r.all_checks_pass() ? "all tolerance checks pass" : "SOME TOLERANCE CHECKS FAIL"});
  Table chain;
  chain.title = "From field data to grid azimuth";
  chain.columns = {"quantity", "value", "sigma", "how"};
  chain.numeric = {false, true, true, false};
  chain.rows = {
      {"gyro azimuth A_G (mean of the line's determinations)", dir(c.gyro_azimuth_rad.value, 2),
       sig(c.gyro_azimuth_rad.sigma, 2), fmt::format("{} determinations; A_G = r - N_G", r.determinations.size())},
      {"instrument constant E", sec(r.instrument_constant_used_rad.value, 2), sig(r.instrument_constant_used_rad.sigma, 2),
       r.instrument_constant ? "calibrated on the known line" : "given"},
      {"astronomic azimuth A = A_G + E", dir(c.astronomic_azimuth_rad.value, 2), sig(c.astronomic_azimuth_rad.sigma, 2), ""},
      {"Laplace correction -eta tan(phi)", c.laplace_applied ? sec(c.laplace_correction_rad, 2) : "not applied", "",
       c.laplace_applied ? "eta at the station" : "eta unknown"},
      {"geodetic azimuth alpha", dir(c.geodetic_azimuth_rad.value, 2), sig(c.geodetic_azimuth_rad.sigma, 2), ""},
      {"meridian convergence gamma (subtracted)", dms(c.convergence_rad, 2), "exact", "GeographicLib transverse Mercator"},
      {"arc-to-chord correction delta (added)", c.arc_to_chord_applied ? sec(c.arc_to_chord_rad, 2) : "not applied",
       c.arc_to_chord_applied ? "exact" : "", c.arc_to_chord_applied ? "rigorous, from the geodesic" : "no target coordinates"},
      {"grid azimuth T = alpha - gamma + delta", dir(c.grid_azimuth_rad.value, 2), sig(c.grid_azimuth_rad.sigma, 2), ""}};
  result.blocks.push_back(chain);
  doc.sections.push_back(result);

  Section checks{"checks", "Tolerance checks", {}, 2};
  CheckList cl;
  for (const auto& k : r.checks) {
    const int dec = k.unit == "div" ? 2 : 1;
    const std::string unit = k.unit == "div" ? " div" : "\"";
    cl.checks.push_back({k.name, fmt::format("{:.{}f}{}", k.value, dec, unit),
                         fmt::format("{:.{}f}{}", k.tolerance, dec, unit), k.pass});
  }
  checks.blocks.push_back(cl);
  doc.sections.push_back(checks);

  if (r.instrument_constant && in.known_line) {
    Section cal{"calibration", "Calibration on the known line", {}, 2};
    cal.blocks.push_back(KeyValueList{"", {{"known azimuth given", fmt::format("{} ({})", dir(in.known_line->azimuth.value_rad.value, 2),
                                                                              in.known_line->azimuth.kind == gyro::KnownAzimuth::Kind::Grid ? "grid"
                                                                              : in.known_line->azimuth.kind == gyro::KnownAzimuth::Kind::Geodetic ? "geodetic"
                                                                                                                                                 : "astronomic")},
                                           {"known astronomic azimuth used", dir(r.known_astronomic_azimuth_rad->value, 2) + "  sigma " +
                                                                                 sig(r.known_astronomic_azimuth_rad->sigma, 1)}}});
    Table t;
    t.columns = {"when", "label", "method", "N_G", "sigma", "A_G", "E", "sigma E"};
    t.numeric = {false, false, false, true, true, true, true, true};
    std::vector<std::string> labels;
    std::vector<gyro::Uncertain> es;
    auto rows = [&](const char* when, const std::vector<gyro::DeterminationResult>& d,
                    const std::vector<gyro::Uncertain>& ag, const std::vector<gyro::Uncertain>& e) {
      for (std::size_t i = 0; i < d.size(); ++i) {
        t.rows.push_back({when, d[i].label, d[i].primary.method, dir(d[i].primary.north.north_rad, 2),
                          sig(d[i].primary.north.sigma_rad, 1), dir(ag[i].value, 2), sec(e[i].value, 2), sig(e[i].sigma, 1)});
        labels.push_back(std::string(when) + " " + label_of(d[i], i));
        es.push_back(e[i]);
      }
    };
    rows("before", r.known_before, r.known_gyro_azimuths_before, r.instrument_constant->before);
    rows("after", r.known_after, r.known_gyro_azimuths_after, r.instrument_constant->after);
    t.note = fmt::format("E = A_known - A_G. Mean E = {} (sigma {}).", sec(r.instrument_constant->mean.value, 2),
                         sig(r.instrument_constant->mean.sigma, 2));
    cal.blocks.push_back(t);
    cal.blocks.push_back(spread_plot("Instrument constant per determination", labels, es, r.instrument_constant->mean.value,
                                     r.instrument_constant->mean.sigma, "E minus mean E (arcsec)",
                                     "Points: E of each determination with +-1 sigma; band: sigma of the mean E."));
    doc.sections.push_back(cal);
  }

  Section line{"line", "Determinations on the line " + line_name, {}, 2};
  {
    Table t;
    t.columns = {"#", "label", "mode", "method", "N_G", "sigma", "target reading", "A_G", "sigma A_G"};
    t.numeric = {true, false, false, false, true, true, true, true, true};
    std::vector<std::string> labels;
    for (std::size_t i = 0; i < r.determinations.size(); ++i) {
      const auto& d = r.determinations[i];
      const auto& din = in.line.determinations[i];
      t.rows.push_back({std::to_string(i + 1), d.label, gyro::to_string(d.mode), d.primary.method,
                        dir(d.primary.north.north_rad, 2), sig(d.primary.north.sigma_rad, 1),
                        din.target_reading_rad ? dir(din.target_reading_rad->value, 1) : "",
                        dir(r.gyro_azimuths[i].value, 2), sig(r.gyro_azimuths[i].sigma, 1)});
      labels.push_back(label_of(d, i));
    }
    t.note = fmt::format("Mean A_G = {}; sigma propagated {}, empirical {}; the larger is used.",
                         dir(r.gyro_azimuth_mean.mean.value, 2), sig(r.gyro_azimuth_mean.sigma_propagated, 2),
                         sig(r.gyro_azimuth_mean.sigma_empirical, 2));
    line.blocks.push_back(t);
    line.blocks.push_back(spread_plot("Gyro azimuth per determination", labels, r.gyro_azimuths,
                                      r.gyro_azimuth_mean.mean.value, r.gyro_azimuth_mean.mean.sigma,
                                      "A_G minus mean A_G (arcsec)",
                                      "Points: A_G of each determination with +-1 sigma; band: sigma of the mean."));
  }
  doc.sections.push_back(line);

  auto details = [&](const std::string& prefix, const std::string& title,
                     const std::vector<gyro::DeterminationInput>& ins,
                     const std::vector<gyro::DeterminationResult>& res) {
    for (std::size_t i = 0; i < res.size(); ++i)
      doc.sections.push_back(Section{fmt::format("{}-{}", prefix, i + 1),
                                     fmt::format("{} {}: {}", title, i + 1, label_of(res[i], i)),
                                     determination_blocks(ins[i], res[i]), 3});
  };
  if (in.known_line) {
    details("known-before", "Known line, before", in.known_line->before, r.known_before);
    details("known-after", "Known line, after", in.known_line->after, r.known_after);
  }
  details("line-determination", "Line", in.line.determinations, r.determinations);

  Section notes{"notes", "Notes and warnings", {}, 2};
  notes.blocks.push_back(Notes{"Warnings", r.warnings, true});
  notes.blocks.push_back(Notes{"Notes", r.notes, false});
  if (r.warnings.empty()) notes.blocks.push_back(Paragraph{"No warnings."});
  doc.sections.push_back(notes);
  return doc;
}

}  // namespace meridian::report
