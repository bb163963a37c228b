#include "meridian/io/dov_writers.hpp"

#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "meridian/core/units.hpp"
#include "dov_names.hpp"

namespace meridian::io {

std::string dov_line_csv_header(bool model, bool truth, const std::string& settings) {
  std::string out = "# meridian dov line: C_b^n (lgu_ij) and C_b^n' (ins_ij), rows E, N, U\n";
  if (!settings.empty()) {
    std::string one_line = settings;
    for (char& ch : one_line)
      if (ch == '\n' || ch == '\r') ch = ' ';
    out += "# " + one_line + "\n";
  }
  out += "time_s,lat_deg,lon_deg,height_m,speed_m_s";
  for (const char* p : {"lgu", "ins"})
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) out += "," + detail::dov_element_column(p, i, j);
  if (model) out += ",model_eta_arcsec,model_xi_arcsec";
  if (truth) out += ",truth_eta_arcsec,truth_xi_arcsec";
  out += "\n";
  return out;
}

void append_dov_line_csv_rows(std::string& out, const std::vector<dov::Sample>& samples,
                              const std::vector<dov::Truth>& truth, bool model,
                              bool truth_columns) {
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const dov::Sample& s = samples[k];
    out += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}", s.time_s,
                       s.lat_rad / units::kDegree, s.lon_rad / units::kDegree, s.height_m,
                       s.speed_m_s);
    for (const Eigen::Matrix3d* m : {&s.lgu_body_to_nav, &s.ins_body_to_nav})
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) out += fmt::format(",{:.17g}", (*m)(i, j));
    if (model)
      out += fmt::format(",{:.17g},{:.17g}", units::rad_to_arcsec(s.model_eta_rad),
                         units::rad_to_arcsec(s.model_xi_rad));
    if (truth_columns)
      out += fmt::format(",{:.17g},{:.17g}", units::rad_to_arcsec(truth[k].eta_rad),
                         units::rad_to_arcsec(truth[k].xi_rad));
    out += "\n";
  }
}

std::string dov_line_csv(const dov::Input& input, const std::string& settings) {
  const bool truth = !input.truth.empty();
  std::string out = dov_line_csv_header(true, truth, settings);
  append_dov_line_csv_rows(out, input.samples, input.truth, true, truth);
  return out;
}

std::string dov_simulation_config_yaml(const DovSimulationConfig& c) {
  // The configuration names the line relative to its own directory.
  const auto config_dir = std::filesystem::absolute(c.config_path).parent_path();
  const auto line = std::filesystem::relative(std::filesystem::absolute(c.line_path), config_dir);
  return fmt::format("# meridian dov process configuration (spec defaults)\n"
                     "line: {}\n"
                     "sigma_model_arcsec: {}\n"
                     "sigma_obs_arcsec: {}\n{}",
                     line.string(), c.sigma_model_arcsec,
                     c.sigma_ins_arcsec > 0.0 ? c.sigma_ins_arcsec : 0.5,
                     c.transport_rate ? "transport_rate: true\n" : "");
}

}  // namespace meridian::io
