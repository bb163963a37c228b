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

double north_deg(const gyro::StochasticSeries& s, double m_arcsec) {
  double deg = (s.reference_rad + units::arcsec_to_rad(m_arcsec)) / units::kDegree;
  deg = std::fmod(deg, 360.0);
  if (deg < 0.0) deg += 360.0;
  return deg;
}

std::string north_dms(const gyro::StochasticSeries& s, double m_arcsec) {
  return format_direction_dms(Angle::radians(s.reference_rad + units::arcsec_to_rad(m_arcsec)),
                              {2, true, false});
}

// A fit's centre M with its σ: the north reading (tracking) or the zero position.
void put_centre(nlohmann::json& j, const gyro::StochasticSeries& s, const Uncertain& centre) {
  if (s.tracking) {
    j["north_reading_deg"] = north_deg(s, centre.value);
    j["north_reading_dms"] = north_dms(s, centre.value);
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

}  // namespace

nlohmann::json stochastic_to_json(const std::string& file, const gyro::StochasticBookResult& book) {
  nlohmann::json out{{"file", file}, {"series", nlohmann::json::array()}};
  for (const auto& s : book.series) {
    const std::string u = s.tracking ? "arcsec" : "div";
    nlohmann::json js{
        {"label", s.label},
        {"kind", s.tracking ? "tracking" : "zero-position"},
        {"readings", s.result.readings},
        {"models", nlohmann::json::array()},
        {"recommended",
         gyro::to_string(s.result.models[static_cast<std::size_t>(s.result.recommended)].model)},
        {"tests", nlohmann::json::array()},
        {"notes", s.result.notes},
        {"warnings", s.result.warnings},
        {"booked_sigma_reading_" + u, json_number(s.input.booked_sigma)},
        {"r2_misfit_rms_" + u, json_number(s.result.r2_misfit_rms)}};
    for (const auto& m : s.result.models) {
      nlohmann::json jm{{"name", gyro::to_string(m.model)}};
      put_centre(jm, s, m.north);
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
      jm["covariance_parameters"] = m.covariance_parameters;
      jm["vce_iterations"] = m.vce_iterations;
      jm["recommended"] = m.recommended;
      jm["degenerate"] = m.degenerate;
      jm["degenerate_reason"] =
          m.degenerate ? nlohmann::json(m.degenerate_reason) : nlohmann::json();
      if (m.r1) {
        const auto& r1 = *m.r1;
        nlohmann::json jr;
        put_centre(jr, s, r1.centre);
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
      js["models"].push_back(jm);
    }
    for (const auto& t : s.result.tests)
      js["tests"].push_back({{"null", gyro::to_string(t.null_model)},
                             {"alternative", gyro::to_string(t.alternative)},
                             {"statistic", json_number(t.statistic)},
                             {"dof", t.dof},
                             {"p_value", json_number(t.p_value)},
                             {"rejected", t.rejected}});
    out["series"].push_back(js);
  }
  return out;
}

std::string stochastic_text(const std::string& file, const gyro::StochasticBookResult& book) {
  std::string o = fmt::format("Stochastic models of reversal-point series: {}\n", file);
  const auto f = [](double x, int d) {
    return std::isfinite(x) ? fmt::format("{:.{}f}", x, d) : std::string("-");
  };
  for (const auto& s : book.series) {
    o += fmt::format("\n{} — {} readings ({})\n", s.label, s.result.readings,
                     s.tracking ? "circle, arcsec" : "scale, div");
    o += fmt::format(
        "{:<16} {:>16} {:>8} {:>16} {:>8} {:>10} {:>8} {:>17} {:>13} {:>13} {:>8} {:>9} {:>8} "
        "{:>8}\n",
        "model", s.tracking ? "north reading" : "centre [div]", "m",
        s.tracking ? "north (R1)" : "centre (R1)", "m", "amplitude", "m", "rho | shape", "sigma1",
        "sigma2", "signal", "lnL", "AIC", "BIC");
    for (const auto& m : s.result.models) {
      std::string rho;
      for (std::size_t k = 0; k < m.rho.size(); ++k) rho += (k ? "," : "") + f(m.rho[k], 3);
      if (c_type(m.model)) {
        rho = "b=" + f(m.shape[0], 2);
        if (m.shape.size() > 1) rho += ",w=" + f(m.shape[1], 2);
      }
      const std::string centre =
          s.tracking ? north_dms(s, m.north.value) : f(m.north.value, 4);
      const std::string centre_r1 =
          !m.r1 ? "-" : (s.tracking ? north_dms(s, m.r1->centre.value) : f(m.r1->centre.value, 4));
      o += fmt::format(
          "{:<16} {:>16} {:>8} {:>16} {:>8} {:>10} {:>8} {:>17} {:>13} {:>13} {:>8} {:>9} {:>8} "
          "{:>8}{}\n",
          gyro::to_string(m.model), centre, f(m.north.sigma, s.tracking ? 2 : 4), centre_r1,
          m.r1 ? f(m.r1->centre.sigma, s.tracking ? 2 : 4) : "-", f(m.amplitude.value, 2), f(m.amplitude.sigma, 2), rho.empty() ? "-" : rho,
          f(m.sigma1.value, 2) + "±" + f(m.sigma1.sigma, 2),
          f(m.sigma2.value, 2) + "±" + f(m.sigma2.sigma, 2), f(m.signal_influence(0), 2),
          f(m.log_likelihood, 2), f(m.aic, 2), f(m.bic, 2),
          m.recommended ? "  <- recommended" : (m.degenerate ? "  degenerate" : ""));
    }
    o += fmt::format(
        "(m, sigma1, sigma2 and signal, the influence of the predicted signal on M, in {}; "
        "rho of the Markov models; shape b [lags] and w [rad/lag] of the covariance functions; "
        "north/centre and amplitude of the linearised model (R2); (R1): the centre of the "
        "non-linear model by GLS with the same covariance)\n",
        s.tracking ? "arcsec" : "div");
    for (const auto& w : s.result.warnings) o += "WARNING: " + w + "\n";
    for (const auto& t : s.result.tests)
      o += fmt::format("LRT {} against {}: 2·ΔlnL = {:.3f}, {} dof, p = {:.4f}: {}\n",
                       gyro::to_string(t.null_model), gyro::to_string(t.alternative), t.statistic,
                       t.dof, t.p_value, t.rejected ? "null rejected at 5 %" : "null kept at 5 %");
    for (const auto& m : s.result.models)
      for (const auto& n : m.notes)
        o += fmt::format("note ({}): {}\n", gyro::to_string(m.model), n);
    for (const auto& n : s.result.notes) o += "note: " + n + "\n";
    o += fmt::format(
        "recommended: {} (smallest BIC among the non-degenerate models)\n",
        gyro::to_string(s.result.models[static_cast<std::size_t>(s.result.recommended)].model));
  }
  return o;
}

Document stochastic_document(const std::string& file, const gyro::StochasticBookResult& book) {
  using nlohmann::json;
  Document doc;
  doc.title = "Stochastic models of reversal-point series";
  doc.subtitle = "white noise, covariance functions, Markov-1 and Markov-2 (gyro-stochastic spec)";
  doc.header.push_back({"field book", file});
  doc.header.push_back({"series", std::to_string(book.series.size())});
  doc.footer = report_generator();
  const auto f = [](double x, int d) {
    return std::isfinite(x) ? fmt::format("{:.{}f}", x, d) : std::string("-");
  };
  for (std::size_t i = 0; i < book.series.size(); ++i) {
    const auto& s = book.series[i];
    const auto& res = s.result;
    const std::string u = s.tracking ? "arcsec" : "div";
    Section sec;
    sec.id = fmt::format("series-{}", i + 1);
    sec.title = fmt::format("{} — {} readings", s.label, res.readings);
    const auto& rec = res.models[static_cast<std::size_t>(res.recommended)];
    sec.blocks.push_back(Highlight{
        "recommended model", gyro::to_string(rec.model),
        s.tracking ? fmt::format("north reading {} ± {}″", north_dms(s, rec.north.value),
                                 f(rec.north.sigma, 2))
                   : fmt::format("centre {} ± {} div", f(rec.north.value, 4), f(rec.north.sigma, 4)),
        false});
    if (!res.warnings.empty()) sec.blocks.push_back(Notes{"Warnings", res.warnings, true});
    Table t;
    t.title = "Model comparison";
    t.columns = {"model",
                 s.tracking ? "north reading" : "centre [div]",
                 "m [" + u + "]",
                 s.tracking ? "north reading (R1)" : "centre (R1) [div]",
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
    t.numeric = {false, true, true, true, true, true, true, false, true, true, true, true, true, true,
                 false};
    for (const auto& m : res.models) {
      std::string rho;
      for (std::size_t k = 0; k < m.rho.size(); ++k) rho += (k ? ", " : "") + f(m.rho[k], 3);
      if (c_type(m.model)) {
        rho = "b = " + f(m.shape[0], 2);
        if (m.shape.size() > 1) rho += ", ω = " + f(m.shape[1], 2);
      }
      t.rows.push_back({gyro::to_string(m.model),
                        s.tracking ? north_dms(s, m.north.value) : f(m.north.value, 4),
                        f(m.north.sigma, s.tracking ? 2 : 4),
                        !m.r1 ? "-"
                              : (s.tracking ? north_dms(s, m.r1->centre.value)
                                            : f(m.r1->centre.value, 4)),
                        m.r1 ? f(m.r1->centre.sigma, s.tracking ? 2 : 4) : "-",
                        f(m.amplitude.value, 2),
                        f(m.amplitude.sigma, 2), rho.empty() ? "-" : rho,
                        f(m.sigma1.value, 3) + " ± " + f(m.sigma1.sigma, 3),
                        f(m.sigma2.value, 3) + " ± " + f(m.sigma2.sigma, 3),
                        f(m.signal_influence(0), 2), f(m.log_likelihood, 2), f(m.aic, 2),
                        f(m.bic, 2),
                        m.recommended ? "recommended" : (m.degenerate ? "degenerate" : "")});
    }
    t.note =
        "North reading / centre and amplitude of the linearised model (R2); (R1): the centre of "
        "the non-linear model r_i = M + (−1)^i·A·e^(−iκ) by GLS with the same covariance. "
        "rho: Markov coefficients; shape: b in lags and ω in rad per lag of the covariance "
        "functions. Recommended: smallest BIC among the non-degenerate models.";
    sec.blocks.push_back(t);
    if (!res.tests.empty()) {
      Table lt;
      lt.title = "Likelihood-ratio tests (α = 5 %)";
      lt.columns = {"null model", "alternative", "2·ΔlnL", "dof", "p", "decision"};
      lt.numeric = {false, false, true, true, true, false};
      for (const auto& x : res.tests)
        lt.rows.push_back({gyro::to_string(x.null_model), gyro::to_string(x.alternative),
                           f(x.statistic, 3), std::to_string(x.dof), f(x.p_value, 4),
                           x.rejected ? "null rejected" : "null kept"});
      sec.blocks.push_back(lt);
    }
    std::vector<std::string> notes;
    for (const auto& m : res.models)
      for (const auto& n : m.notes) notes.push_back(gyro::to_string(m.model) + ": " + n);
    notes.insert(notes.end(), res.notes.begin(), res.notes.end());
    if (!notes.empty()) sec.blocks.push_back(Notes{"Notes", notes, false});
    // Residual autocorrelation (OLS) against each model's implied autocorrelation.
    const std::size_t lags = static_cast<std::size_t>(std::max(2, res.readings / 2)) + 1;
    json values = json::array();
    for (std::size_t k = 0; k < lags && k < res.residual_autocorrelation.size(); ++k)
      values.push_back({{"lag", k},
                        {"r", json_number(res.residual_autocorrelation[k])},
                        {"model", "OLS residuals"}});
    for (const auto& m : res.models)
      for (std::size_t k = 0; k < lags && k < m.implied_autocorrelation.size(); ++k)
        values.push_back({{"lag", k},
                          {"r", json_number(m.implied_autocorrelation[k])},
                          {"model", gyro::to_string(m.model)}});
    json acf = {
        {"width", 600},
        {"height", 260},
        {"data", {{"values", values}}},
        {"mark", {{"type", "line"}, {"point", true}}},
        {"encoding",
         {{"x", {{"field", "lag"}, {"type", "quantitative"}, {"title", "lag (readings)"}}},
          {"y", {{"field", "r"}, {"type", "quantitative"}, {"title", "autocorrelation"}}},
          {"color", {{"field", "model"}, {"type", "nominal"}, {"title", ""}}}}}};
    sec.blocks.push_back(Plot{"Residual autocorrelation and the models' implied autocorrelation",
                              acf,
                              "OLS residuals: ĉ_k/ĉ_0 with ĉ_k = Σ v_i v_{i+k}/n (biased low at "
                              "long lags by the 3 fitted unknowns); models: the mean correlation "
                              "D_{i,i+k}/√(D_ii D_{i+k,i+k})."});
    if (res.markov2_surface.size() > 0) {
      json cells = json::array();
      for (Eigen::Index a = 0; a < res.markov2_surface.rows(); ++a)
        for (Eigen::Index b = 0; b < res.markov2_surface.cols(); ++b)
          if (std::isfinite(res.markov2_surface(a, b)))
            cells.push_back({{"rho1", res.rho1_grid[static_cast<std::size_t>(a)]},
                             {"rho2", res.rho2_grid[static_cast<std::size_t>(b)]},
                             {"lnL", res.markov2_surface(a, b)}});
      json surf = {
          {"width", 420},
          {"height", 380},
          {"data", {{"values", cells}}},
          {"mark", "rect"},
          {"encoding",
           {{"x", {{"field", "rho1"}, {"type", "ordinal"}, {"title", "rho1"},
                   {"axis", {{"format", ".1f"}}}}},
            {"y", {{"field", "rho2"}, {"type", "ordinal"}, {"title", "rho2"},
                   {"sort", "descending"}, {"axis", {{"format", ".1f"}}}}},
            {"color", {{"field", "lnL"}, {"type", "quantitative"}, {"title", "REML lnL"}}},
            {"tooltip", json::array({{{"field", "rho1"}}, {{"field", "rho2"}},
                                     {{"field", "lnL"}, {"format", ".2f"}}})}}}};
      sec.blocks.push_back(Plot{"Markov-2: profile restricted likelihood over (rho1, rho2)", surf,
                                "The likelihood is maximised over the variance components at "
                                "every grid point; cells outside the stationarity triangle or "
                                "where it has no maximum with sigma1 > 0 are empty."});
    }
    doc.sections.push_back(std::move(sec));
  }
  return doc;
}

}  // namespace meridian::report
