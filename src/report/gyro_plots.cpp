// Vega-Lite plots of gyro observations and results for the HTML reports.
#include "gyro_plots.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "meridian/core/angle.hpp"
#include "meridian/core/units.hpp"
#include "meridian/report/format.hpp"

namespace meridian::report::gyro_plots {
namespace {

using fmtx::num;
using nlohmann::json;
constexpr int kPlotWidth = 620;

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

// The oscillation (N1) drawn in the plot: a(t) = β + B·e^{−k(t−t0)}·sin(2π(t − t0)/T).
struct Oscillation {
  double beta = 0, amplitude = 0, t0 = 0, period = 0, damping = 0;
  std::string caption;
};

std::optional<Oscillation> oscillation_of(const gyro::UnifiedFitResult& f) {
  return Oscillation{f.beta_div.value, f.amplitude_div.value, f.t0_s.value, f.period_s.value, f.damping_per_s.value,
                     "Line: the unified least-squares fit of (N1). "};
}

// A closed-form method's β, B and T_B, with the phase of its first timed
// passage (sin θ = (a − β)/B on the passage's side of the swing), k = 0.
std::optional<Oscillation> oscillation_of(const gyro::DeterminationInput& in, const gyro::BetaResult& b) {
  if (!b.amplitude_div || !b.period_s || !(b.amplitude_div->value > 0.0)) return std::nullopt;
  for (const auto& c : in.nontracking.crossings) {
    if (c.times_s.empty()) continue;
    const double q = std::clamp((c.level_div - b.beta_div.value) / b.amplitude_div->value, -1.0, 1.0);
    const double theta = c.first_direction > 0 ? std::asin(q) : units::kPi - std::asin(q);
    const double T = b.period_s->value;
    return Oscillation{b.beta_div.value, b.amplitude_div->value, c.times_s.front() - T * theta / (2 * units::kPi), T,
                       0.0,
                       "Line: (N1) with this method's beta, B and T_B and the phase of the first timed passage "
                       "(k = 0). "};
  }
  return std::nullopt;
}

// Turning-point times of the model for reversal readings given without
// times: successive turning points on the reading's side.
std::vector<double> reversal_times(const gyro::DeterminationInput& in, const Oscillation& f) {
  const auto& o = in.nontracking;
  if (!o.reversal_times_s.empty()) return o.reversal_times_s;
  double t_first = std::numeric_limits<double>::infinity();
  for (const auto& c : o.crossings)
    if (!c.times_s.empty()) t_first = std::min(t_first, c.times_s.front());
  if (!std::isfinite(t_first)) t_first = f.t0;
  const double T = f.period, t0 = f.t0;
  // Turning point k at t0 + T/4 + k·T/2: east (+) for even k. Start at the
  // first turning point after t_first − T/4 (readings are taken while timing).
  long k = static_cast<long>(std::ceil((t_first - T / 4 - t0 - T / 4) / (T / 2)));
  std::vector<double> out;
  for (double a : o.reversals_div) {
    const bool east = a > f.beta;
    while (((k % 2 + 2) % 2 == 0) != east) ++k;
    out.push_back(t0 + T / 4 + static_cast<double>(k) * T / 2);
    ++k;
  }
  return out;
}

}  // namespace

Plot oscillation_plot(const gyro::DeterminationInput& in, const gyro::UnifiedFitResult* unified,
                      const gyro::BetaResult* method) {
  const auto& o = in.nontracking;
  const double beta_div = method ? method->beta_div.value : unified ? unified->beta_div.value : 0.0;
  std::optional<Oscillation> fit;
  if (unified) fit = oscillation_of(*unified);
  else if (method) fit = oscillation_of(in, *method);
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
    caption += "Reversal readings were not timed: they are drawn at the model's turning points. ";
  json layers = json::array();
  if (fit) {
    const double T = fit->period, t0 = fit->t0, B = fit->amplitude;
    const double k = fit->damping, b = fit->beta;
    const double lo = tmin - T / 8, hi = tmax + T / 8;
    json curve = json::array();
    for (int i = 0; i <= 400; ++i) {
      const double t = lo + (hi - lo) * i / 400.0;
      curve.push_back({{"t", t}, {"a", b + B * std::exp(-k * (t - t0)) * std::sin(2 * units::kPi * (t - t0) / T)}});
    }
    layers.push_back({{"data", {{"values", curve}}},
                      {"mark", {{"type", "line"}, {"color", "#0b5cad"}, {"strokeWidth", 1.5}}},
                      {"encoding", {{"x", axis("t", "time (s)")}, {"y", axis("a", "scale reading (div, east +)")}}}});
    caption += fit->caption;
  } else {
    caption += "No model for this method (no amplitude and period); the dashed line is beta. ";
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
    const double d =
        wrap_signed_rad(m.north.north_rad - r.primary.north.north_rad) / units::kArcsecond;
    const double s = std::isfinite(m.north.sigma_rad) ? m.north.sigma_rad / units::kArcsecond : 0.0;
    v.push_back({{"method", gyro::to_string(m.method)}, {"d", d}, {"lo", d - s}, {"hi", d + s}});
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
          fmt::format("Bars: +-1 sigma. Reported result: {}.", gyro::to_string(r.primary.method))};
}

Plot tracking_plot(const gyro::DeterminationInput& in, const gyro::ReversalResult& fit, const AngleFormat& f) {
  const auto r = gyro::unwrap_circle_readings(in.tracking.reversals_rad);
  const double m = fit.centre.value;
  json v = json::array();
  for (std::size_t i = 0; i < r.size(); ++i) {
    const double obs = wrap_signed_rad(r[i] - m) / units::kArcsecond;
    const double res = i < fit.residuals.size() ? fit.residuals[i] / units::kArcsecond : 0.0;
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
                      f.dir(m, 2), gyro::to_string(fit.method))};
}

Plot tracking_residual_plot(const gyro::ReversalResult& fit) {
  json v = json::array();
  for (std::size_t i = 0; i < fit.residuals.size(); ++i)
    v.push_back({{"i", static_cast<int>(i + 1)}, {"v", fit.residuals[i] / units::kArcsecond}});
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
  return {
      "Tracking: residuals", spec,
      fmt::format(
          "v = fitted - observed for the {} fit; sigma0 = {} arcsec with {} degrees of freedom.",
          gyro::to_string(fit.method), num(fit.sigma0 / units::kArcsecond, 2), fit.dof)};
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
    const double d = wrap_signed_rad(values[i].value - mean) / units::kArcsecond;
    const double s = values[i].sigma / units::kArcsecond;
    v.push_back({{"label", labels[i]}, {"d", d}, {"lo", d - s}, {"hi", d + s}});
  }
  const double ms = mean_sigma / units::kArcsecond;
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

}  // namespace meridian::report::gyro_plots
