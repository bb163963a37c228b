#include "meridian/report/dov_html.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "meridian/core/units.hpp"

namespace meridian::report {
namespace {

using nlohmann::json;

constexpr std::size_t kMaxDrawn = kDovReportEpochs / 2;  // epochs per plot (a 10 Hz day: 864 000)

double arcsec(double rad) { return units::rad_to_arcsec(rad); }

std::size_t stride(std::size_t n) { return std::max<std::size_t>(1, (n + kMaxDrawn - 1) / kMaxDrawn); }

std::string drawn(std::size_t step) {
  return step == 1 ? "All epochs drawn." : fmt::format("One epoch in {} drawn.", step);
}

json axis(const char* field, const std::string& title, bool zero = true) {
  json a = {{"field", field}, {"type", "quantitative"}, {"title", title}};
  if (!zero) a["scale"] = {{"zero", false}};
  return a;
}

// η or ξ against time: model, filtered, smoothed with its ±σ band.
Plot component_plot(const dov::Result& r, bool eta, std::size_t thinned) {
  const char* name = eta ? "η (east)" : "ξ (north)";
  const std::size_t step = stride(r.epochs.size());
  json band = json::array(), lines = json::array();
  for (std::size_t k = 0; k < r.epochs.size(); k += step) {
    const dov::EpochResult& e = r.epochs[k];
    const double t_min = e.time_s / 60.0;
    const double s = eta ? e.smoothed.eta_rad : e.smoothed.xi_rad;
    const double sigma = eta ? e.smoothed.sigma_eta_rad : e.smoothed.sigma_xi_rad;
    band.push_back({{"t", t_min}, {"lo", arcsec(s - sigma)}, {"hi", arcsec(s + sigma)}});
    lines.push_back({{"t", t_min}, {"v", arcsec(eta ? e.model_eta_rad : e.model_xi_rad)},
                     {"series", "global model"}});
    lines.push_back({{"t", t_min}, {"v", arcsec(eta ? e.filtered.eta_rad : e.filtered.xi_rad)},
                     {"series", "filtered"}});
    lines.push_back({{"t", t_min}, {"v", arcsec(s)}, {"series", "smoothed"}});
    if (e.truth)
      lines.push_back({{"t", t_min},
                       {"v", arcsec(eta ? e.truth->eta_rad : e.truth->xi_rad)},
                       {"series", "truth"}});
  }
  const bool truth = !r.epochs.empty() && r.epochs.front().truth.has_value();
  json domain = {"global model", "filtered", "smoothed"};
  json colours = {"#999999", "#f58518", "#4c78a8"};
  if (truth) {
    domain.push_back("truth");
    colours.push_back("#000000");
  }
  json layers = json::array();
  layers.push_back({{"data", {{"values", band}}},
                    {"mark", {{"type", "area"}, {"opacity", 0.25}, {"color", "#4c78a8"}}},
                    {"encoding",
                     {{"x", axis("t", "time (min)")},
                      {"y", axis("lo", fmt::format("{} (arcsec)", name), false)},
                      {"y2", {{"field", "hi"}}}}}});
  layers.push_back(
      {{"data", {{"values", lines}}},
       {"mark", {{"type", "line"}, {"strokeWidth", 1}}},
       {"encoding",
        {{"x", axis("t", "time (min)")},
         {"y", axis("v", fmt::format("{} (arcsec)", name), false)},
         {"color",
          {{"field", "series"},
           {"type", "nominal"},
           {"title", ""},
           {"scale",
            {{"domain", domain}, {"range", colours}}}}}}}});
  return {fmt::format("{}: global model, filtered and smoothed{}", name,
                      truth ? ", and the truth" : ""),
          json{{"width", 700}, {"height", 240}, {"layer", layers}},
          "Band: smoothed ± σ. " + drawn(step * thinned)};
}

Plot innovation_plot(const dov::Result& r, std::size_t thinned) {
  const std::size_t step = stride(r.epochs.size());
  json values = json::array(), band = json::array();
  for (std::size_t k = 0; k < r.epochs.size(); k += step) {
    const dov::EpochResult& e = r.epochs[k];
    const double t_min = e.time_s / 60.0;
    values.push_back({{"t", t_min}, {"v", arcsec(e.innovation_east_rad)}, {"series", "ν_E"}});
    values.push_back({{"t", t_min}, {"v", arcsec(e.innovation_north_rad)}, {"series", "ν_N"}});
    const double s = arcsec(std::max(e.sigma_innovation_east_rad, e.sigma_innovation_north_rad));
    band.push_back({{"t", t_min}, {"lo", -2.0 * s}, {"hi", 2.0 * s}});
  }
  json layers = json::array();
  layers.push_back({{"data", {{"values", band}}},
                    {"mark", {{"type", "area"}, {"opacity", 0.2}, {"color", "#999999"}}},
                    {"encoding",
                     {{"x", axis("t", "time (min)")},
                      {"y", axis("lo", "innovation (arcsec)")},
                      {"y2", {{"field", "hi"}}}}}});
  layers.push_back({{"data", {{"values", values}}},
                    {"mark", {{"type", "line"}, {"strokeWidth", 1}}},
                    {"encoding",
                     {{"x", axis("t", "time (min)")},
                      {"y", axis("v", "innovation (arcsec)")},
                      {"color", {{"field", "series"}, {"type", "nominal"}, {"title", ""}}}}}});
  return {"Innovations of the attitude-difference observations",
          json{{"width", 700}, {"height", 200}, {"layer", layers}},
          "ν = y − H·x̂⁻ per epoch, east and north. Grey band: ±2√S, the filter's own 2σ of the "
          "innovation (the larger of east and north). " + drawn(step * thinned)};
}

std::string pair_text(const dov::EtaXi& v) {
  return fmt::format("η {:.3f}″, ξ {:.3f}″", arcsec(v.eta_rad), arcsec(v.xi_rad));
}

// The report's header: where the line came from and the model it was processed with.
std::vector<KeyValue> dov_header(const dov::Result& r) {
  const dov::Options& o = r.options;
  const dov::Origin& from = r.origin;
  const dov::Summary& s = r.summary;
  return {
      {"input", from.input},
      {"line", from.line.empty() ? from.input : from.line},
      {"global model", from.model.empty() ? "η_G, ξ_G columns of the line" : from.model},
      {"epochs", fmt::format("{} ({} in the statistics)", s.epochs, s.statistics_epochs)},
      {"model error", fmt::format("second-order Gauss–Markov, σ {:.2f}″, ζ {:.3f}, λ {:.0f} m",
                                  arcsec(o.model.sigma_model_rad), o.model.zeta,
                                  o.model.correlation_length_m)},
      {"observation σ", fmt::format("east {:.2f}″, north {:.2f}″", arcsec(o.sigma_obs_east_rad),
                                    arcsec(o.sigma_obs_north_rad))},
      {"discretisation", o.discretisation == dov::DiscretisationMethod::Exact
                             ? "exact (Van Loan)"
                             : "published first order"},
      {"extraction", o.extraction == dov::Extraction::Exact ? "exact (log map)" : "skew part"},
      {"attitude dynamics",
       o.transport_rate ? fmt::format("Earth rate + transport rate from the track ({} s baselines, "
                                      "{} closed)",
                                      o.transport_rate_baseline_s, s.transport_rate_updates)
                        : std::string("Earth rate only")}};
}

// The summary section: σ, ε_U, the NIS check, the figures and the signs.
Section dov_summary_section(const dov::Summary& s) {
  Section summary{"summary", "Summary", {}, 2};
  summary.blocks.push_back(
      Highlight{"smoothed σ (quadratic mean)", pair_text(s.rms_sigma_smoothed),
                fmt::format("filtered: {}", pair_text(s.rms_sigma_filtered)), false});
  summary.blocks.push_back(Highlight{
      "vertical gyro bias ε_U",
      fmt::format("{:.5f} ± {:.5f} °/h", s.eps_u_rad_s / units::kDegree * 3600.0,
                  s.sigma_eps_u_rad_s / units::kDegree * 3600.0),
      "smoothed", false});
  CheckList checks{"Consistency", {}};
  checks.checks.push_back({"mean NIS (2 degrees of freedom)", fmt::format("{:.3f}", s.mean_nis),
                           fmt::format("[{:.3f}, {:.3f}]", s.nis_interval.lower, s.nis_interval.upper),
                           s.nis_interval.contains(s.mean_nis),
                           "95 % interval of the mean of χ²(2) values"});
  if (s.whiteness.lags > 0)
    checks.checks.push_back(
        {fmt::format("innovation whiteness (Ljung–Box, {} lags)", s.whiteness.lags),
         fmt::format("Q = {:.1f}", s.whiteness.q),
         fmt::format("≤ {:.1f}", s.whiteness.critical_value), s.whiteness.pass,
         fmt::format("χ²({:g}) at α = {:g}, normalised innovations, both components",
                     s.whiteness.dof, s.whiteness.alpha)});
  summary.blocks.push_back(checks);
  KeyValueList kv{"Figures", {}};
  kv.items.push_back({"gate rejections", std::to_string(s.rejected)});
  kv.items.push_back({"discretisations of the model", std::to_string(s.discretisations)});
  kv.items.push_back({"stationary steps",
                      fmt::format("{} (V < {:g} m/s)", s.stationary_steps, s.stationary_speed_m_s)});
  kv.items.push_back({"P₀ reference speed", fmt::format("{:.4g} m/s", s.reference_speed_m_s)});
  if (s.rms_model) kv.items.push_back({"RMS error of the global model", pair_text(*s.rms_model)});
  if (s.rms_filtered) kv.items.push_back({"RMS error filtered", pair_text(*s.rms_filtered)});
  if (s.rms_smoothed) kv.items.push_back({"RMS error smoothed", pair_text(*s.rms_smoothed)});
  if (s.mean_nees_smoothed)
    kv.items.push_back({"mean NEES smoothed (8 states)", fmt::format("{:.3f}", *s.mean_nees_smoothed)});
  summary.blocks.push_back(kv);
  summary.blocks.push_back(Paragraph{
      "η > 0: the astronomic zenith (the upward plumb line) lies east of the ellipsoid normal; "
      "ξ > 0: north of it (astronomic minus geodetic). σ is the filter's standard deviation of "
      "δη̂, δξ̂, the estimate's departure from the global model, under the model-error model "
      "(σ_model, ζ, λ). An error of the global model that is constant over the whole line is "
      "not observable from the attitude difference and is not in σ."});
  return summary;
}

}  // namespace

Document dov_document(const dov::Result& r) {
  const std::size_t thinned = std::max<std::size_t>(1, r.epoch_stride);
  Document doc;
  doc.title = "Dynamic deflection of the vertical";
  doc.subtitle = r.origin.input;
  doc.footer = report_generator();
  doc.header = dov_header(r);
  doc.sections.push_back(dov_summary_section(r.summary));

  Section profile{"profile", "Profile", {}, 2};
  profile.blocks.push_back(component_plot(r, true, thinned));
  profile.blocks.push_back(component_plot(r, false, thinned));
  doc.sections.push_back(profile);

  Section innov{"innovations", "Innovations", {}, 2};
  innov.blocks.push_back(innovation_plot(r, thinned));
  doc.sections.push_back(innov);

  Section notes{"notes", "Notes", {}, 2};
  if (!r.warnings.empty()) notes.blocks.push_back(Notes{"Warnings", r.warnings, true});
  notes.blocks.push_back(Notes{"Notes", r.notes.empty() ? std::vector<std::string>{"none"} : r.notes,
                               false});
  doc.sections.push_back(notes);
  return doc;
}

}  // namespace meridian::report
