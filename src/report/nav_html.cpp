#include "meridian/report/nav_html.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "meridian/report/format.hpp"
#include "nav_support.hpp"

namespace meridian::report {
namespace {

using fmtx::num;
using nlohmann::json;
using namespace nav_detail;

constexpr std::size_t kNavMaxDrawn = 2000;     // points of one method per plot
constexpr std::size_t kNavMaxRejectedRows = 1000;  // rows of the rejected table
constexpr std::size_t kNavMaxSkippedRows = 200;
constexpr int kNavPlotWidth = 640;

// Indices of a series of n points drawn: every step-th from the first, and the last; at most
// kNavMaxDrawn.
struct NavDrawn {
  std::vector<std::size_t> index;
  std::size_t step = 1;
};

NavDrawn nav_drawn(std::size_t n) {
  NavDrawn d;
  if (n == 0) return d;
  d.step = n <= kNavMaxDrawn ? 1 : (n - 1 + kNavMaxDrawn - 2) / (kNavMaxDrawn - 1);
  for (std::size_t k = 0; k < n; k += d.step) d.index.push_back(k);
  if (d.index.back() != n - 1) d.index.push_back(n - 1);
  return d;
}

std::string nav_drawn_caption(std::size_t step) {
  return step == 1 ? "Every epoch is drawn."
                   : fmt::format("One epoch in {} (and the last) is drawn, at most {} per method; "
                                 "the statistics use every epoch.",
                                 step, kNavMaxDrawn);
}

double nav_rounded(double v, double unit) { return std::round(v / unit) * unit; }

// One colour per method, the same in every plot.
const char* nav_colour(nav::Method m) {
  switch (m) {
    case nav::Method::DeadReckoning: return "#7f7f7f";
    case nav::Method::SequentialNoBias: return "#e45756";
    case nav::Method::SequentialBiasI: return "#f58518";
    case nav::Method::SequentialBiasII: return "#b8a22a";
    case nav::Method::Backward: return "#b279a2";
    case nav::Method::FixClosure: return "#9d755d";
    case nav::Method::Ekf: return "#54a24b";
    case nav::Method::Rts: return "#4c78a8";
  }
  return "#000000";
}

// The colour of each method shown.
json nav_colour_encoding(const std::vector<nav::Method>& shown) {
  json domain = json::array(), range = json::array();
  for (nav::Method m : shown) {
    domain.push_back(nav::to_string(m));
    range.push_back(nav_colour(m));
  }
  return {{"field", "m"}, {"type", "nominal"}, {"title", "method"},
          {"scale", {{"domain", domain}, {"range", range}}}};
}

json nav_axis(const char* field, const std::string& title, bool zero = false) {
  json a = {{"field", field}, {"type", "quantitative"}, {"title", title}};
  if (!zero) a["scale"] = {{"zero", false}};
  return a;
}

double nav_t0(const nav::Result& r) {
  for (const auto& m : r.methods)
    if (!m.track.empty()) return m.track.front().time_s;
  return 0.0;
}

// Every method in the x/y plane, east across and north up, one metre the same length on both
// axes.
Plot nav_track_plot(const nav::Result& r) {
  json values = json::array();
  std::vector<nav::Method> shown;
  double e_lo = std::numeric_limits<double>::infinity(), e_hi = -e_lo, n_lo = e_lo, n_hi = -e_lo;
  std::size_t step = 1;
  for (const auto& m : r.methods) {
    if (m.track.empty()) continue;
    shown.push_back(m.method);
    const NavDrawn d = nav_drawn(m.track.size());
    step = std::max(step, d.step);
    for (std::size_t k : d.index) {
      const nav::TrackPoint& p = m.track[k];
      if (!std::isfinite(p.x_north_m) || !std::isfinite(p.y_east_m)) continue;
      values.push_back({{"m", nav::to_string(m.method)},
                        {"i", k},
                        {"t", nav_rounded(p.time_s, 1e-3)},
                        {"e", nav_rounded(p.y_east_m, 0.01)},
                        {"n", nav_rounded(p.x_north_m, 0.01)}});
      e_lo = std::min(e_lo, p.y_east_m);
      e_hi = std::max(e_hi, p.y_east_m);
      n_lo = std::min(n_lo, p.x_north_m);
      n_hi = std::max(n_hi, p.x_north_m);
    }
  }
  if (values.empty()) e_lo = e_hi = n_lo = n_hi = 0.0;
  // Equal scale: metres per pixel the same across and up; the shorter extent is widened.
  double span_e = std::max(e_hi - e_lo, 1.0), span_n = std::max(n_hi - n_lo, 1.0);
  const int height =
      static_cast<int>(std::clamp(kNavPlotWidth * span_n / span_e, 240.0, double(kNavPlotWidth)));
  span_e *= 1.06;
  span_n *= 1.06;
  if (span_n / height > span_e / kNavPlotWidth)
    span_e = span_n * kNavPlotWidth / height;
  else
    span_n = span_e * height / kNavPlotWidth;
  const double ce = 0.5 * (e_lo + e_hi), cn = 0.5 * (n_lo + n_hi);
  auto axis = [](const char* field, const char* title, double lo, double hi) {
    return json{{"field", field},
                {"type", "quantitative"},
                {"title", title},
                {"scale", {{"domain", {lo, hi}}, {"nice", false}, {"zero", false}}},
                {"axis", {{"tickCount", 6}, {"labelOverlap", "greedy"}, {"format", ".0f"}}}};
  };
  json spec = {
      {"width", kNavPlotWidth},
      {"height", height},
      {"data", {{"values", values}}},
      {"mark", {{"type", "line"}, {"strokeWidth", 1.2}, {"clip", true}}},
      {"encoding",
       {{"x", axis("e", "y, east (m)", ce - 0.5 * span_e, ce + 0.5 * span_e)},
        {"y", axis("n", "x, north (m)", cn - 0.5 * span_n, cn + 0.5 * span_n)},
        {"order", {{"field", "i"}, {"type", "quantitative"}}},
        {"color", nav_colour_encoding(shown)},
        {"tooltip", json::array({{{"field", "m"}, {"title", "method"}},
                                 {{"field", "t"}, {"title", "time (s)"}},
                                 {{"field", "n"}, {"title", "x north (m)"}},
                                 {{"field", "e"}, {"title", "y east (m)"}}})}}}};
  return {"Track of every method",
          spec,
          "Plane coordinates of the job, east across and north up, one scale on both axes. " +
              nav_drawn_caption(step)};
}

// The per-minute RMS error of every method with truth on one plot.
Plot nav_error_plot(const nav::Result& r) {
  json values = json::array();
  std::vector<nav::Method> shown;
  bool positive = true;
  std::size_t step = 1;
  for (const auto& m : r.methods) {
    if (!m.errors) continue;
    shown.push_back(m.method);
    const auto& bins = m.errors->per_minute_rms_m;
    const NavDrawn d = nav_drawn(bins.size());
    step = std::max(step, d.step);
    for (std::size_t j : d.index) {
      if (!std::isfinite(bins[j])) continue;  // a minute without truth: a gap
      positive = positive && bins[j] > 0.0;
      values.push_back({{"m", nav::to_string(m.method)},
                        {"minute", j},
                        {"v", nav_rounded(bins[j], 1e-3)}});
    }
  }
  json minute_axis = nav_axis("minute", "minute from the first epoch", true);
  minute_axis["axis"] = {{"tickMinStep", 1}, {"format", "d"}};
  json y = nav_axis("v", "RMS position error (m)", true);
  if (positive) y["scale"] = {{"type", "log"}};
  json spec = {{"width", kNavPlotWidth},
               {"height", 300},
               {"data", {{"values", values}}},
               {"mark", {{"type", "line"}, {"point", true}, {"strokeWidth", 1.2}}},
               {"encoding",
                {{"x", minute_axis},
                 {"y", y},
                 {"color", nav_colour_encoding(shown)},
                 {"tooltip", json::array({{{"field", "m"}, {"title", "method"}},
                                          {{"field", "minute"}, {"title", "minute"}},
                                          {{"field", "v"}, {"title", "RMS (m)"}}})}}}};
  return {"Position error per minute, every method",
          spec,
          std::string("RMS of the horizontal position error against truth in each minute j "
                      "(j ≤ t − t₀ < j + 1 min, t₀ the first epoch); minutes without truth are "
                      "left out.") +
              (positive ? " Logarithmic scale." : "") +
              (step == 1 ? "" : fmt::format(" One minute in {} drawn.", step))};
}

// The bias component against time: every method that estimates one, the ±σ band where the
// method states σ (EKF, smoother).
Plot nav_bias_plot(const nav::Result& r, bool north) {
  const double t0 = nav_t0(r);
  json lines = json::array();
  std::vector<std::pair<nav::Method, json>> bands;  // one band layer per method with σ
  std::vector<nav::Method> shown;
  std::size_t step = 1;
  for (const auto& m : r.methods) {
    if (!estimates_bias(m.method) || m.track.empty()) continue;
    shown.push_back(m.method);
    const NavDrawn d = nav_drawn(m.track.size());
    step = std::max(step, d.step);
    json band = json::array();
    for (std::size_t k : d.index) {
      const nav::TrackPoint& p = m.track[k];
      const double t = nav_rounded((p.time_s - t0) / 60.0, 1e-4);
      const double b = north ? p.bias_north_m_s : p.bias_east_m_s;
      const double s = stated_sigma(north ? p.sigma_bias_north_m_s : p.sigma_bias_east_m_s);
      if (!std::isfinite(b)) continue;
      lines.push_back({{"m", nav::to_string(m.method)}, {"t", t}, {"b", nav_rounded(b, 1e-5)}});
      if (std::isfinite(s))
        band.push_back({{"m", nav::to_string(m.method)},
                        {"t", t},
                        {"lo", nav_rounded(b - s, 1e-5)},
                        {"hi", nav_rounded(b + s, 1e-5)}});
    }
    if (!band.empty()) bands.emplace_back(m.method, band);
  }
  const std::string ytitle = north ? "bias W_N (m/s)" : "bias W_E (m/s)";
  const json time_axis = nav_axis("t", "time from the first epoch (min)", true);
  json layers = json::array();
  // Bands in the method's colour, without a legend of their own (the lines carry it).
  for (const auto& [method, band] : bands)
    layers.push_back({{"data", {{"values", band}}},
                      {"mark", {{"type", "area"}, {"opacity", 0.18}, {"color", nav_colour(method)}}},
                      {"encoding",
                       {{"x", time_axis}, {"y", nav_axis("lo", ytitle)}, {"y2", {{"field", "hi"}}}}}});
  layers.push_back({{"data", {{"values", lines}}},
                    {"mark", {{"type", "line"}, {"strokeWidth", 1.2}}},
                    {"encoding",
                     {{"x", time_axis}, {"y", nav_axis("b", ytitle)}, {"color", nav_colour_encoding(shown)}}}});
  return {north ? "Velocity bias, north component" : "Velocity bias, east component",
          json{{"width", kNavPlotWidth}, {"height", 220}, {"layer", layers}},
          "The correction W added to the DR velocity, as each method estimates it at each epoch. " +
              std::string(bands.empty() ? "" : "Bands: ± σ where the method states it (EKF, smoother). ") +
              nav_drawn_caption(step)};
}

std::string nav_bias_cell(const nav::MethodResult& m, bool north) {
  if (!estimates_bias(m.method) || m.track.empty()) return "not estimated";
  const nav::TrackPoint& p = m.track.back();
  const double b = north ? p.bias_north_m_s : p.bias_east_m_s;
  const double s = stated_sigma(north ? p.sigma_bias_north_m_s : p.sigma_bias_east_m_s);
  return std::isfinite(s) ? fmt::format("{:+.4f} ± {:.4f}", b, s) : fmt::format("{:+.4f}", b);
}

// The methods side by side: errors against truth (or σ without it), final bias, rejections.
Table nav_methods_table(const nav::Result& r, bool truth) {
  Table t;
  t.title = "Methods side by side";
  if (truth) {
    t.columns = {"method", "RMS (m)", "max (m)", "mean NEES", "final bias N (m/s)",
                 "final bias E (m/s)", "rejected LOPs", "flagged fixes", "status"};
    t.numeric = {false, true, true, true, true, true, true, true, false};
  } else {
    t.columns = {"method", "final σx (m)", "final σy (m)", "mean σ (m)", "max σ (m)",
                 "final bias N (m/s)", "final bias E (m/s)", "rejected LOPs", "flagged fixes", "status"};
    t.numeric = {false, true, true, true, true, true, true, true, true, false};
  }
  for (const auto& m : r.methods) {
    std::vector<std::string> row{nav::to_string(m.method)};
    if (truth) {
      row.push_back(m.errors ? num(m.errors->rms_m, 2) : "n/a");
      row.push_back(m.errors ? num(m.errors->max_error_m, 2) : "n/a");
      row.push_back(m.errors ? num(m.errors->mean_nees, 2) : "n/a");
    } else {
      const SigmaSummary sg = sigma_summary(m);
      for (double v : {sg.final_x, sg.final_y, sg.mean_h, sg.max_h}) row.push_back(nav_sigma_cell(m, num(v, 2)));
    }
    row.push_back(nav_bias_cell(m, true));
    row.push_back(nav_bias_cell(m, false));
    const RejectionCounts c = rejection_counts(r, m.method);
    const auto from = observations_of(m.method);
    row.push_back(from ? "as " + nav::to_string(*from) : std::to_string(c.lops));
    row.push_back(from ? "as " + nav::to_string(*from) : std::to_string(c.fixes));
    row.push_back(nav_status_text(m));
    t.rows.push_back(row);
  }
  t.note = std::string(truth ? "RMS and max: horizontal position error against truth. Mean NEES of (x, y): 2 "
                               "when σ is consistent with the errors. "
                             : "No truth: no error statistics. σ: the final σ of x and y; mean and max "
                               "over the line of the horizontal σ = √(σx² + σy²); the notes say which "
                               "methods' σ are rigorous. ") +
           "Bias: the correction to the DR velocity at the last epoch, ± σ where the method states "
           "one. Rejected: by the method's own screening; backward and fix-closure use the "
           "observations sequential-bias-I accepted, rts those the ekf accepted. Status: the "
           "method's self-checks from the data alone (no truth); a diverged or inconsistent "
           "method's σ are not valid (\"(not valid)\" beside them).";
  return t;
}

// The failed self-checks of every method (no rows: every method consistent).
Table nav_alarms_table(const nav::Result& r) {
  Table t;
  t.title = "Self-checks that failed";
  t.columns = {"method", "status", "from (s)", "to (s)", "epochs", "check", "reason"};
  t.numeric = {false, false, true, true, false, false, false};
  for (const auto& m : r.methods)
    for (const auto& a : m.consistency.alarms)
      t.rows.push_back({nav::to_string(m.method), nav::to_string(a.status), num(a.from_s, 1), num(a.to_s, 1),
                        fmt::format("{}–{}", a.from_epoch, a.to_epoch), a.check, a.reason});
  t.note = "Each method checks itself without truth: fix misclosures against the combined σ (a run of "
           "consecutive outlying fixes: diverged), the share of rejected LOPs and the spread of the "
           "normalised innovations per window. Its σ are not valid over these stretches; do not use "
           "its track there.";
  return t;
}

// The chain parameters of every method (no rows: none estimated).
Table nav_parameters_table(const nav::Result& r) {
  Table p;
  p.title = "Chain parameters";
  p.columns = {"method", "chain", "parameter", "value", "σ"};
  p.numeric = {false, false, false, true, true};
  for (const auto& m : r.methods)
    for (const auto& q : m.parameters) {
      const bool scale = q.name == "scale";
      p.rows.push_back({nav::to_string(m.method), q.chain_name.empty() ? std::to_string(q.chain) : q.chain_name,
                        q.name,
                        !std::isfinite(q.value) ? "n/a"
                        : scale                 ? fmt::format("{:+.3e}", q.value)
                                                : fmt::format("{:+.3f}", q.value),
                        !std::isfinite(q.sigma) ? "n/a"
                        : scale                 ? fmt::format("{:.3e}", q.sigma)
                                                : fmt::format("{:.3f}", q.sigma)});
    }
  p.note = "scale: dimensionless (L = (1 + scale)·d + offset); offset_m in metres. At the last "
           "epoch (the smoother: over the whole line).";
  return p;
}

Section nav_summary_section(const nav::Result& r, bool truth) {
  Section sec{"summary", "Summary", {}, 2};
  if (truth) {
    const nav::MethodResult* best = nullptr;
    for (const auto& m : r.methods)
      if (m.errors && std::isfinite(m.errors->rms_m) && (!best || m.errors->rms_m < best->errors->rms_m))
        best = &m;
    if (best)
      sec.blocks.push_back(Highlight{"lowest RMS position error",
                                     fmt::format("{}: {:.2f} m", nav::to_string(best->method),
                                                 best->errors->rms_m),
                                     fmt::format("max {:.2f} m over {} epochs with truth",
                                                 best->errors->max_error_m, best->errors->epochs),
                                     false});
  }
  sec.blocks.push_back(nav_methods_table(r, truth));
  if (Table a = nav_alarms_table(r); !a.rows.empty()) sec.blocks.push_back(a);
  KeyValueList kv{"Observations", {}};
  kv.items.push_back({"epochs", std::to_string(r.epochs)});
  kv.items.push_back({"LOPs reduced to an epoch", std::to_string(r.lops_used)});
  kv.items.push_back({"satellite fixes used", std::to_string(r.fixes_used)});
  kv.items.push_back({"rejections (all methods)", std::to_string(r.rejected.size())});
  kv.items.push_back({"skipped (no method could use them)", std::to_string(r.skipped.size())});
  sec.blocks.push_back(kv);
  if (Table p = nav_parameters_table(r); !p.rows.empty()) sec.blocks.push_back(p);
  return sec;
}

Section nav_rejected_section(const nav::Result& r) {
  Section sec{"rejected", "Rejected observations", {}, 2};
  if (r.rejected.empty()) {
    sec.blocks.push_back(Paragraph{"No method rejected an observation."});
  } else {
    Table t;
    t.title = "Rejected by a method";
    t.columns = {"kind", "index", "source", "method", "time (s)", "misclosure (m)", "statistic", "reason"};
    t.numeric = {false, true, false, false, true, true, true, false};
    for (std::size_t i = 0; i < std::min(r.rejected.size(), kNavMaxRejectedRows); ++i) {
      const auto& o = r.rejected[i];
      t.rows.push_back({kind_name(o.kind), std::to_string(o.index), o.source.empty() ? "n/a" : o.source,
                        nav::to_string(o.method), num(o.time_s, 1), num(o.misclosure_m, 1), num(o.statistic, 2),
                        o.reason});
    }
    t.note = "index: 0-based into the input's LOPs or fixes; source: its file and line. misclosure: "
             "observed − computed (a fix: its distance from the track). statistic: |w| of a LOP's "
             "w-test, √χ² of a fix, 0 under the misclosure threshold.";
    if (r.rejected.size() > kNavMaxRejectedRows)
      t.note += fmt::format(" The first {} of {} rows are shown; the rejected CSV lists all.",
                            kNavMaxRejectedRows, r.rejected.size());
    sec.blocks.push_back(t);
  }
  if (!r.skipped.empty()) {
    Table s;
    s.title = "Skipped (no method could use them)";
    s.columns = {"kind", "index", "source", "time (s)", "reason"};
    s.numeric = {false, true, false, true, false};
    for (std::size_t i = 0; i < std::min(r.skipped.size(), kNavMaxSkippedRows); ++i) {
      const auto& o = r.skipped[i];
      s.rows.push_back({kind_name(o.kind), std::to_string(o.index), o.source.empty() ? "n/a" : o.source,
                        num(o.time_s, 1), o.reason});
    }
    if (r.skipped.size() > kNavMaxSkippedRows)
      s.note = fmt::format("The first {} of {} are shown; the JSON lists all.", kNavMaxSkippedRows,
                           r.skipped.size());
    sec.blocks.push_back(s);
  }
  return sec;
}

}  // namespace

Document nav_document(const nav::Result& r, const std::string& title) {
  const bool truth = std::any_of(r.methods.begin(), r.methods.end(),
                                 [](const nav::MethodResult& m) { return m.errors.has_value(); });
  Document doc;
  doc.title = title;
  doc.subtitle = "Marine navigation: dead reckoning, lines of position and satellite fixes";
  doc.footer = report_generator();
  std::string methods;
  for (const auto& m : r.methods) methods += (methods.empty() ? "" : ", ") + nav::to_string(m.method);
  doc.header.push_back({"methods", methods.empty() ? "none" : methods});
  doc.header.push_back({"epochs", std::to_string(r.epochs)});
  for (const auto& m : r.methods)
    if (!m.track.empty()) {
      doc.header.push_back({"time span", fmt::format("{:.1f} … {:.1f} s ({:.1f} min)",
                                                     m.track.front().time_s, m.track.back().time_s,
                                                     (m.track.back().time_s - m.track.front().time_s) / 60.0)});
      break;
    }
  doc.header.push_back({"truth", truth ? "yes: error statistics against it" : "no"});

  doc.sections.push_back(nav_summary_section(r, truth));

  Section track{"track", "Track", {}, 2};
  track.blocks.push_back(nav_track_plot(r));
  doc.sections.push_back(track);

  Section errors{"errors", "Errors against truth", {}, 2};
  if (truth)
    errors.blocks.push_back(nav_error_plot(r));
  else
    errors.blocks.push_back(Paragraph{"The line has no truth: no error curves."});
  doc.sections.push_back(errors);

  Section bias{"bias", "Velocity-bias estimates", {}, 2};
  const bool any_bias = std::any_of(r.methods.begin(), r.methods.end(), [](const nav::MethodResult& m) {
    return estimates_bias(m.method) && !m.track.empty();
  });
  if (any_bias) {
    bias.blocks.push_back(nav_bias_plot(r, true));
    bias.blocks.push_back(nav_bias_plot(r, false));
  } else {
    bias.blocks.push_back(Paragraph{"No method of this run estimates the DR velocity bias."});
  }
  doc.sections.push_back(bias);

  doc.sections.push_back(nav_rejected_section(r));

  Section notes{"notes", "Notes", {}, 2};
  if (!r.warnings.empty()) notes.blocks.push_back(Notes{"Warnings", r.warnings, true});
  notes.blocks.push_back(
      Notes{"Notes", r.notes.empty() ? std::vector<std::string>{"none"} : r.notes, false});
  doc.sections.push_back(notes);
  return doc;
}

}  // namespace meridian::report
