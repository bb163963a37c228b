#include "meridian/report/gyro_stochastic.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "json_number.hpp"
#include "meridian/core/angle.hpp"
#include "meridian/core/dms.hpp"
#include "meridian/core/units.hpp"

namespace meridian::report {
namespace {

using detail::json_number;

nlohmann::json nums(const std::vector<double>& v) {
  nlohmann::json a = nlohmann::json::array();
  for (double x : v) a.push_back(json_number(x));
  return a;
}

bool tracking(const gyro::StochasticResult& r) { return r.kind == gyro::SeriesKind::Circle; }

double north_deg(const gyro::StochasticResult& r, double m_arcsec) {
  double deg = (r.reference_rad + units::arcsec_to_rad(m_arcsec)) / units::kDegree;
  deg = std::fmod(deg, 360.0);
  if (deg < 0.0) deg += 360.0;
  return deg;
}

std::string north_dms(const gyro::StochasticResult& r, double m_arcsec) {
  return format_direction_dms(Angle::radians(r.reference_rad + units::arcsec_to_rad(m_arcsec)),
                              {2, true, false});
}

// A fit's centre M with its σ: the north reading (tracking) or the zero position.
void put_centre(nlohmann::json& j, const gyro::StochasticResult& r, const Uncertain& centre) {
  if (tracking(r)) {
    j["north_reading_deg"] = north_deg(r, centre.value);
    j["north_reading_dms"] = north_dms(r, centre.value);
    j["sigma_north_arcsec"] = json_number(centre.sigma);
  } else {
    j["zero_position_div"] = json_number(centre.value);
    j["sigma_zero_position_div"] = json_number(centre.sigma);
  }
}

bool c_type(gyro::StochasticModel m) {
  return m == gyro::StochasticModel::Exponential || m == gyro::StochasticModel::Gaussian ||
         m == gyro::StochasticModel::DampedCosine;
}

// x with d decimals, "-" when it is not finite.
std::string fixed(double x, int d) { return std::isfinite(x) ? fmt::format("{:.{}f}", x, d) : std::string("-"); }

// A centre M as a north reading (DMS; tracking) or a zero position (div), and its σ.
std::string centre_text(const gyro::StochasticResult& r, double m) {
  return tracking(r) ? north_dms(r, m) : fixed(m, 4);
}
std::string centre_sigma_text(const gyro::StochasticResult& r, double sigma) {
  return fixed(sigma, tracking(r) ? 2 : 4);
}

// The Markov coefficients, or a covariance function's shape: "0.412,0.100" and "b=1.20,w=0.52"
// (text) or "0.412, 0.100" and "b = 1.20, ω = 0.52" (report).
std::string rho_shape(const gyro::ModelFit& m, const char* sep, const char* b, const char* w) {
  std::string rho;
  for (std::size_t k = 0; k < m.rho.size(); ++k) rho += (k ? sep : "") + fixed(m.rho[k], 3);
  if (c_type(m.model)) {
    rho = b + fixed(m.shape[0], 2);
    if (m.shape.size() > 1) rho += sep + std::string(w) + fixed(m.shape[1], 2);
  }
  return rho.empty() ? "-" : rho;
}

const gyro::ModelFit& recommended(const gyro::StochasticResult& r) {
  return r.models[static_cast<std::size_t>(r.recommended)];
}

// --- JSON

nlohmann::json model_json(const gyro::StochasticResult& r, const gyro::ModelFit& m) {
  const std::string u = gyro::fitted_unit(r.kind);
  nlohmann::json jm{{"name", gyro::to_string(m.model)}};
  put_centre(jm, r, m.north);
  jm["amplitude_" + u] = json_number(m.amplitude.value);
  jm["sigma_amplitude_" + u] = json_number(m.amplitude.sigma);
  jm["rho"] = nums(m.rho);
  jm["rho_sigma"] = nums(m.rho_sigma);
  if (m.shape.empty()) {
    jm["shape"] = nullptr;
  } else {
    nlohmann::json sh{{"b_lags", json_number(m.shape[0])}};
    if (m.shape.size() > 1) sh["omega_rad_per_lag"] = json_number(m.shape[1]);
    jm["shape"] = sh;
  }
  jm["sigma1_" + u] = json_number(m.sigma1.value);
  jm["sigma1_sigma_" + u] = json_number(m.sigma1.sigma);
  jm["sigma2_" + u] = json_number(m.sigma2.value);
  jm["sigma2_sigma_" + u] = json_number(m.sigma2.sigma);
  jm["signal_influence_" + u] = json_number(m.signal_influence(0));
  jm["signal_influence_amplitude_" + u] = json_number(m.signal_influence(1));
  jm["log_likelihood"] = json_number(m.log_likelihood);
  jm["aic"] = json_number(m.aic);
  jm["bic"] = json_number(m.bic);
  jm["aicc"] = json_number(m.aicc);
  jm["covariance_parameters"] = m.covariance_parameters;
  jm["vce_iterations"] = m.vce_iterations;
  jm["recommended"] = m.recommended;
  jm["degenerate"] = m.degenerate;
  jm["degenerate_reason"] = m.degenerate ? nlohmann::json(m.degenerate_reason) : nlohmann::json();
  if (m.r1) {
    const auto& r1 = *m.r1;
    nlohmann::json jr;
    put_centre(jr, r, r1.centre);
    jr["amplitude_" + u] = json_number(r1.amplitude.value);
    jr["sigma_amplitude_" + u] = json_number(r1.amplitude.sigma);
    jr["decay_per_half_period"] = json_number(r1.decay.value);
    jr["sigma_decay_per_half_period"] = json_number(r1.decay.sigma);
    jr["iterations"] = r1.iterations;
    jm["r1"] = jr;
  } else {
    jm["r1"] = nullptr;
  }
  jm["notes"] = m.notes;
  return jm;
}

nlohmann::json series_json(const gyro::StochasticSeries& s) {
  const gyro::StochasticResult& r = s.result;
  const std::string u = gyro::fitted_unit(r.kind);
  nlohmann::json js{{"label", s.label},
                    {"kind", tracking(r) ? "tracking" : "zero-position"},
                    {"readings", r.readings},
                    {"models", nlohmann::json::array()},
                    {"recommended", gyro::to_string(recommended(r).model)},
                    {"tests", nlohmann::json::array()},
                    {"notes", r.notes},
                    {"warnings", r.warnings},
                    {"booked_sigma_reading_" + u, json_number(r.booked_sigma)},
                    {"r2_misfit_rms_" + u, json_number(r.r2_misfit_rms)}};
  for (const auto& m : r.models) js["models"].push_back(model_json(r, m));
  js["recommendation_reason"] = r.recommendation_reason;
  {
    // The value to use: the recommended model's, or white noise's without the outliers.
    nlohmann::json jr{{"model", gyro::to_string(recommended(r).model)},
                      {"without_outliers", r.without_outliers.has_value()},
                      {"reason", r.recommendation_reason}};
    put_centre(jr, r, r.answer);
    jr["interval95_half_width_" + u] = json_number(r.answer_half95);
    jr["sigma_basis"] = r.answer_basis;
    js["recommendation"] = jr;
  }
  js["interval95_factor"] = json_number(gyro::interval95_factor(r.readings));
  js["outliers"] = nlohmann::json::array();
  for (const auto& x : r.outliers)
    js["outliers"].push_back({{"reading", x.reading},
                              {"w", json_number(x.w)},
                              {"t", json_number(x.t)},
                              {"critical", json_number(x.critical)},
                              {"dof", x.dof},
                              {"error_" + u, json_number(x.error.value)},
                              {"sigma_error_" + u, json_number(x.error.sigma)}});
  if (r.without_outliers) {
    const auto& w = *r.without_outliers;
    nlohmann::json jw{{"readings_used", w.readings_used}, {"dof", w.dof}};
    put_centre(jw, r, w.north);
    jw["amplitude_" + u] = json_number(w.amplitude.value);
    jw["sigma_amplitude_" + u] = json_number(w.amplitude.sigma);
    jw["sigma1_" + u] = json_number(w.sigma1);
    js["without_outliers"] = jw;
  } else {
    js["without_outliers"] = nullptr;
  }
  for (const auto& t : r.tests)
    js["tests"].push_back({{"null", gyro::to_string(t.null_model)},
                           {"alternative", gyro::to_string(t.alternative)},
                           {"statistic", json_number(t.statistic)},
                           {"dof", t.dof},
                           {"p_value", json_number(t.p_value)},
                           {"rejected", t.rejected}});
  return js;
}

// --- text

// The readings with their white-noise residuals (and the residuals without the outliers).
std::string readings_text(const gyro::StochasticResult& r) {
  const std::string u = gyro::fitted_unit(r.kind);
  std::string o = fmt::format("readings and white-noise residuals v = G·Y - L [{}]:\n", u);
  for (int i = 0; i < r.readings; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const bool out = std::any_of(r.outliers.begin(), r.outliers.end(),
                                 [&](const gyro::ReadingOutlier& x) { return x.reading == i + 1; });
    o += fmt::format("  {:>3} {:>14} {:>10}{}\n", i + 1, fixed(r.fitted_readings[k], tracking(r) ? 2 : 4),
                     fixed(r.ols_residuals(i), tracking(r) ? 2 : 4), out ? "  outlier" : "");
  }
  return o;
}

std::string outliers_text(const gyro::StochasticResult& r) {
  const std::string u = gyro::fitted_unit(r.kind);
  std::string o;
  if (r.outliers.empty())
    return fmt::format(
        "data snooping (white noise, sigma from the other readings, alpha0 = {}): no outlier\n",
        gyro::kSnoopingAlpha0);
  for (const auto& x : r.outliers)
    o += fmt::format(
        "OUTLIER: reading {} (data snooping, white noise: t = {:.2f} > {:.2f}, {} dof, w = {:.2f}): "
        "error {} ± {} {}\n",
        x.reading, x.t, x.critical, x.dof - 1, x.w, fixed(x.error.value, 2), fixed(x.error.sigma, 2), u);
  if (r.without_outliers) {
    const auto& w = *r.without_outliers;
    const auto& white = r.fit(gyro::StochasticModel::WhiteNoise);
    o += fmt::format(
        "without the outlier(s): white noise {} ± {} ({} readings, sigma1 {} {}); with them {} ± {}\n",
        centre_text(r, w.north.value), centre_sigma_text(r, w.north.sigma), w.readings_used,
        fixed(w.sigma1, 2), u, centre_text(r, white.north.value), centre_sigma_text(r, white.north.sigma));
  }
  return o;
}

// The recommendation in one line, with its value, its 95 % interval and the reason.
std::string recommendation_text(const gyro::StochasticResult& r) {
  return fmt::format("recommended: {} {} ± {} (95 %: ± {}; sigma: {}) — {}\n",
                     gyro::to_string(recommended(r).model), centre_text(r, r.answer.value),
                     centre_sigma_text(r, r.answer.sigma), centre_sigma_text(r, r.answer_half95),
                     r.answer_basis, r.recommendation_reason);
}

std::string series_text(const gyro::StochasticSeries& s) {
  const gyro::StochasticResult& r = s.result;
  const bool tr = tracking(r);
  std::string o = fmt::format("\n{} — {} readings ({})\n", s.label, r.readings,
                              tr ? "circle, arcsec" : "scale, div");
  o += fmt::format(
      "{:<16} {:>16} {:>8} {:>16} {:>8} {:>10} {:>8} {:>17} {:>13} {:>13} {:>8} {:>9} {:>8} "
      "{:>8} {:>8}\n",
      "model", tr ? "north reading" : "centre [div]", "m", tr ? "north (R1)" : "centre (R1)", "m",
      "amplitude", "m", "rho | shape", "sigma1", "sigma2", "signal", "lnL", "AIC", "BIC", "AICc");
  for (const auto& m : r.models)
    o += fmt::format(
        "{:<16} {:>16} {:>8} {:>16} {:>8} {:>10} {:>8} {:>17} {:>13} {:>13} {:>8} {:>9} {:>8} "
        "{:>8} {:>8}{}\n",
        gyro::to_string(m.model), centre_text(r, m.north.value), centre_sigma_text(r, m.north.sigma),
        m.r1 ? centre_text(r, m.r1->centre.value) : "-", m.r1 ? centre_sigma_text(r, m.r1->centre.sigma) : "-",
        fixed(m.amplitude.value, 2), fixed(m.amplitude.sigma, 2), rho_shape(m, ",", "b=", "w="),
        fixed(m.sigma1.value, 2) + "±" + fixed(m.sigma1.sigma, 2),
        fixed(m.sigma2.value, 2) + "±" + fixed(m.sigma2.sigma, 2), fixed(m.signal_influence(0), 2),
        fixed(m.log_likelihood, 2), fixed(m.aic, 2), fixed(m.bic, 2), fixed(m.aicc, 2),
        m.recommended ? "  <- recommended" : (m.degenerate ? "  degenerate" : ""));
  o += fmt::format(
      "(m, sigma1, sigma2 and signal, the influence of the predicted signal on M, in {}; "
      "rho of the Markov models; shape b [lags] and w [rad/lag] of the covariance functions; "
      "north/centre and amplitude of the linearised model (R2); (R1): the centre of the "
      "non-linear model by GLS with the same covariance)\n",
      gyro::fitted_unit(r.kind));
  for (const auto& w : r.warnings) o += "WARNING: " + w + "\n";
  for (const auto& t : r.tests)
    o += fmt::format("LRT {} against {}: 2·ΔlnL = {:.3f}, {} dof, p = {:.4f}: {}\n",
                     gyro::to_string(t.null_model), gyro::to_string(t.alternative), t.statistic, t.dof,
                     t.p_value, t.rejected ? "null rejected at 5 %" : "null kept at 5 %");
  for (const auto& m : r.models)
    for (const auto& n : m.notes) o += fmt::format("note ({}): {}\n", gyro::to_string(m.model), n);
  for (const auto& n : r.notes) o += "note: " + n + "\n";
  o += readings_text(r) + outliers_text(r);
  o += recommendation_text(r);
  return o;
}

// --- report document

Highlight recommended_highlight(const gyro::StochasticResult& r) {
  const auto& rec = recommended(r);
  const Uncertain c = r.answer;
  return Highlight{"recommended model", gyro::to_string(rec.model),
                   (tracking(r) ? fmt::format("north reading {} ± {}″", north_dms(r, c.value),
                                              fixed(c.sigma, 2))
                                : fmt::format("centre {} ± {} div", fixed(c.value, 4), fixed(c.sigma, 4))) +
                       " — " + r.recommendation_reason,
                   false};
}

Table comparison_table(const gyro::StochasticResult& r) {
  const bool tr = tracking(r);
  const std::string u = gyro::fitted_unit(r.kind);
  Table t;
  t.title = "Model comparison";
  t.columns = {"model",
               tr ? "north reading" : "centre [div]",
               "m [" + u + "]",
               tr ? "north reading (R1)" : "centre (R1) [div]",
               "m (R1) [" + u + "]",
               "amplitude [" + u + "]",
               "m [" + u + "]",
               "rho | shape",
               "sigma1 [" + u + "]",
               "sigma2 [" + u + "]",
               "signal ΔM [" + u + "]",
               "lnL",
               "AIC",
               "BIC",
               ""};
  t.numeric = {false, true, true, true, true, true, true, false, true, true, true, true, true, true, false};
  for (const auto& m : r.models)
    t.rows.push_back({gyro::to_string(m.model), centre_text(r, m.north.value),
                      centre_sigma_text(r, m.north.sigma), m.r1 ? centre_text(r, m.r1->centre.value) : "-",
                      m.r1 ? centre_sigma_text(r, m.r1->centre.sigma) : "-", fixed(m.amplitude.value, 2),
                      fixed(m.amplitude.sigma, 2), rho_shape(m, ", ", "b = ", "ω = "),
                      fixed(m.sigma1.value, 3) + " ± " + fixed(m.sigma1.sigma, 3),
                      fixed(m.sigma2.value, 3) + " ± " + fixed(m.sigma2.sigma, 3),
                      fixed(m.signal_influence(0), 2), fixed(m.log_likelihood, 2), fixed(m.aic, 2),
                      fixed(m.bic, 2), m.recommended ? "recommended" : (m.degenerate ? "degenerate" : "")});
  t.note =
      "North reading / centre and amplitude of the linearised model (R2); (R1): the centre of "
      "the non-linear model r_i = M + (−1)^i·A·e^(−iκ) by GLS with the same covariance. "
      "rho: Markov coefficients; shape: b in lags and ω in rad per lag of the covariance "
      "functions. Recommended: " + r.recommendation_reason + ".";
  return t;
}

Table tests_table(const gyro::StochasticResult& r) {
  Table lt;
  lt.title = "Likelihood-ratio tests (α = 5 %)";
  lt.columns = {"null model", "alternative", "2·ΔlnL", "dof", "p", "decision"};
  lt.numeric = {false, false, true, true, true, false};
  for (const auto& x : r.tests)
    lt.rows.push_back({gyro::to_string(x.null_model), gyro::to_string(x.alternative), fixed(x.statistic, 3),
                       std::to_string(x.dof), fixed(x.p_value, 4), x.rejected ? "null rejected" : "null kept"});
  return lt;
}

std::vector<std::string> all_notes(const gyro::StochasticResult& r) {
  std::vector<std::string> notes;
  for (const auto& m : r.models)
    for (const auto& n : m.notes) notes.push_back(gyro::to_string(m.model) + ": " + n);
  notes.insert(notes.end(), r.notes.begin(), r.notes.end());
  return notes;
}

// Residual autocorrelation (OLS) against each model's implied autocorrelation, lags 0 … n/2.
Plot autocorrelation_plot(const gyro::StochasticResult& r) {
  using nlohmann::json;
  const std::size_t lags = static_cast<std::size_t>(std::max(2, r.readings / 2)) + 1;
  json values = json::array();
  for (std::size_t k = 0; k < lags && k < r.residual_autocorrelation.size(); ++k)
    values.push_back(
        {{"lag", k}, {"r", json_number(r.residual_autocorrelation[k])}, {"model", "OLS residuals"}});
  for (const auto& m : r.models)
    for (std::size_t k = 0; k < lags && k < m.implied_autocorrelation.size(); ++k)
      values.push_back({{"lag", k},
                        {"r", json_number(m.implied_autocorrelation[k])},
                        {"model", gyro::to_string(m.model)}});
  json acf = {{"width", 600},
              {"height", 260},
              {"data", {{"values", values}}},
              {"mark", {{"type", "line"}, {"point", true}}},
              {"encoding",
               {{"x", {{"field", "lag"}, {"type", "quantitative"}, {"title", "lag (readings)"}}},
                {"y", {{"field", "r"}, {"type", "quantitative"}, {"title", "autocorrelation"}}},
                {"color", {{"field", "model"}, {"type", "nominal"}, {"title", ""}}}}}};
  return Plot{"Residual autocorrelation and the models' implied autocorrelation", acf,
              "OLS residuals: ĉ_k/ĉ_0 with ĉ_k = Σ v_i v_{i+k}/n (biased low at "
              "long lags by the 3 fitted unknowns); models: the mean correlation "
              "D_{i,i+k}/√(D_ii D_{i+k,i+k})."};
}

// The profile REML of Markov-2 over the (ρ_1, ρ_2) grid.
Plot markov2_surface_plot(const gyro::StochasticResult& r) {
  using nlohmann::json;
  json cells = json::array();
  for (Eigen::Index a = 0; a < r.markov2_surface.rows(); ++a)
    for (Eigen::Index b = 0; b < r.markov2_surface.cols(); ++b)
      if (std::isfinite(r.markov2_surface(a, b)))
        cells.push_back({{"rho1", r.rho1_grid[static_cast<std::size_t>(a)]},
                         {"rho2", r.rho2_grid[static_cast<std::size_t>(b)]},
                         {"lnL", r.markov2_surface(a, b)}});
  json surf = {
      {"width", 420},
      {"height", 380},
      {"data", {{"values", cells}}},
      {"mark", "rect"},
      {"encoding",
       {{"x", {{"field", "rho1"}, {"type", "ordinal"}, {"title", "rho1"}, {"axis", {{"format", ".1f"}}}}},
        {"y",
         {{"field", "rho2"},
          {"type", "ordinal"},
          {"title", "rho2"},
          {"sort", "descending"},
          {"axis", {{"format", ".1f"}}}}},
        {"color", {{"field", "lnL"}, {"type", "quantitative"}, {"title", "REML lnL"}}},
        {"tooltip",
         json::array({{{"field", "rho1"}}, {{"field", "rho2"}}, {{"field", "lnL"}, {"format", ".2f"}}})}}}};
  return Plot{"Markov-2: profile restricted likelihood over (rho1, rho2)", surf,
              "The likelihood is maximised over the variance components at "
              "every grid point; cells outside the stationarity triangle or "
              "where it has no maximum with sigma1 > 0 are empty."};
}

Section series_section(const gyro::StochasticSeries& s, std::size_t index) {
  const gyro::StochasticResult& r = s.result;
  Section sec;
  sec.id = fmt::format("series-{}", index + 1);
  sec.title = fmt::format("{} — {} readings", s.label, r.readings);
  sec.blocks.push_back(recommended_highlight(r));
  if (!r.warnings.empty()) sec.blocks.push_back(Notes{"Warnings", r.warnings, true});
  sec.blocks.push_back(comparison_table(r));
  if (!r.tests.empty()) sec.blocks.push_back(tests_table(r));
  if (const auto notes = all_notes(r); !notes.empty()) sec.blocks.push_back(Notes{"Notes", notes, false});
  sec.blocks.push_back(autocorrelation_plot(r));
  if (r.markov2_surface.size() > 0) sec.blocks.push_back(markov2_surface_plot(r));
  return sec;
}

}  // namespace

nlohmann::json stochastic_to_json(const gyro::StochasticBookResult& book) {
  nlohmann::json out{{"file", book.file}, {"series", nlohmann::json::array()}};
  for (const auto& s : book.series) out["series"].push_back(series_json(s));
  return out;
}

std::string stochastic_text(const gyro::StochasticBookResult& book) {
  std::string o = fmt::format("Stochastic models of reversal-point series: {}\n", book.file);
  for (const auto& s : book.series) o += series_text(s);
  return o;
}

Document stochastic_document(const gyro::StochasticBookResult& book) {
  Document doc;
  doc.title = "Stochastic models of reversal-point series";
  doc.subtitle = "white noise, covariance functions, Markov-1 and Markov-2 (gyro-stochastic spec)";
  doc.header.push_back({"field book", book.file});
  doc.header.push_back({"series", std::to_string(book.series.size())});
  doc.footer = report_generator();
  for (std::size_t i = 0; i < book.series.size(); ++i) doc.sections.push_back(series_section(book.series[i], i));
  return doc;
}

}  // namespace meridian::report
