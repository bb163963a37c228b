#include "meridian/report/gyro_stochastic.hpp"

#include <cmath>

#include <fmt/format.h>

#include "meridian/core/units.hpp"

namespace meridian::report {
namespace {

nlohmann::json num(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); }

nlohmann::json nums(const std::vector<double>& v) {
  nlohmann::json a = nlohmann::json::array();
  for (double x : v) a.push_back(num(x));
  return a;
}

double north_deg(const gyro::StochasticSeries& s, double m_arcsec) {
  double deg = (s.reference_rad + units::arcsec_to_rad(m_arcsec)) / units::kDegree;
  deg = std::fmod(deg, 360.0);
  if (deg < 0.0) deg += 360.0;
  return deg;
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
        {"notes", s.result.notes}};
    for (const auto& m : s.result.models) {
      nlohmann::json jm{{"name", gyro::to_string(m.model)}};
      if (s.tracking) {
        jm["north_reading_deg"] = north_deg(s, m.north.value);
        jm["sigma_north_arcsec"] = num(m.north.sigma);
      } else {
        jm["zero_position_div"] = num(m.north.value);
        jm["sigma_zero_position_div"] = num(m.north.sigma);
      }
      jm["amplitude_" + u] = num(m.amplitude.value);
      jm["sigma_amplitude_" + u] = num(m.amplitude.sigma);
      jm["rho"] = nums(m.rho);
      jm["rho_sigma"] = nums(m.rho_sigma);
      jm["sigma1_" + u] = num(m.sigma1.value);
      jm["sigma1_sigma_" + u] = num(m.sigma1.sigma);
      jm["sigma2_" + u] = num(m.sigma2.value);
      jm["sigma2_sigma_" + u] = num(m.sigma2.sigma);
      jm["signal_influence_" + u] = num(m.signal_influence(0));
      jm["signal_influence_amplitude_" + u] = num(m.signal_influence(1));
      jm["log_likelihood"] = num(m.log_likelihood);
      jm["aic"] = num(m.aic);
      jm["bic"] = num(m.bic);
      jm["covariance_parameters"] = m.covariance_parameters;
      jm["vce_iterations"] = m.vce_iterations;
      jm["recommended"] = m.recommended;
      jm["notes"] = m.notes;
      js["models"].push_back(jm);
    }
    for (const auto& t : s.result.tests)
      js["tests"].push_back({{"null", gyro::to_string(t.null_model)},
                             {"alternative", gyro::to_string(t.alternative)},
                             {"statistic", num(t.statistic)},
                             {"dof", t.dof},
                             {"p_value", num(t.p_value)},
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
        "{:<16} {:>14} {:>8} {:>10} {:>8} {:>15} {:>13} {:>13} {:>8} {:>9} {:>8} {:>8}\n", "model",
        s.tracking ? "north [deg]" : "centre [div]", "m", "amplitude", "m", "rho", "sigma1",
        "sigma2", "signal", "lnL", "AIC", "BIC");
    for (const auto& m : s.result.models) {
      std::string rho;
      for (std::size_t k = 0; k < m.rho.size(); ++k) rho += (k ? "," : "") + f(m.rho[k], 3);
      const std::string centre =
          s.tracking ? fmt::format("{:.6f}", north_deg(s, m.north.value)) : f(m.north.value, 4);
      o += fmt::format(
          "{:<16} {:>14} {:>8} {:>10} {:>8} {:>15} {:>13} {:>13} {:>8} {:>9} {:>8} {:>8}{}\n",
          gyro::to_string(m.model), centre, f(m.north.sigma, s.tracking ? 2 : 4),
          f(m.amplitude.value, 2), f(m.amplitude.sigma, 2), rho.empty() ? "-" : rho,
          f(m.sigma1.value, 2) + "±" + f(m.sigma1.sigma, 2),
          f(m.sigma2.value, 2) + "±" + f(m.sigma2.sigma, 2), f(m.signal_influence(0), 2),
          f(m.log_likelihood, 2), f(m.aic, 2), f(m.bic, 2),
          m.recommended ? "  <- recommended" : "");
    }
    o += fmt::format(
        "(m, sigma1, sigma2 and signal, the influence of the predicted signal on M, in {})\n",
        s.tracking ? "arcsec" : "div");
    for (const auto& t : s.result.tests)
      o += fmt::format("LRT {} against {}: 2·ΔlnL = {:.3f}, {} dof, p = {:.4f}: {}\n",
                       gyro::to_string(t.null_model), gyro::to_string(t.alternative), t.statistic,
                       t.dof, t.p_value, t.rejected ? "null rejected at 5 %" : "null kept at 5 %");
    for (const auto& m : s.result.models)
      for (const auto& n : m.notes)
        o += fmt::format("note ({}): {}\n", gyro::to_string(m.model), n);
    for (const auto& n : s.result.notes) o += "note: " + n + "\n";
    o += fmt::format(
        "recommended: {} (smallest BIC)\n",
        gyro::to_string(s.result.models[static_cast<std::size_t>(s.result.recommended)].model));
  }
  return o;
}

}  // namespace meridian::report
