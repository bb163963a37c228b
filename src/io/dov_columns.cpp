#include "meridian/io/dov_columns.hpp"

#include <initializer_list>
#include <optional>
#include <utility>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"

namespace meridian::io {

DovLineColumns dov_line_columns(const std::vector<dov::Sample>& samples,
                                const std::vector<dov::Truth>& truth, bool model) {
  const std::size_t n = samples.size();
  DovLineColumns c;
  c.has_model = model;
  c.has_truth = !truth.empty();
  for (auto* v : {&c.time_s, &c.lat_deg, &c.lon_deg, &c.height_m, &c.speed_m_s}) v->resize(n);
  c.lgu_body_to_nav.resize(9 * n);
  c.ins_body_to_nav.resize(9 * n);
  if (model) {
    c.model_eta_arcsec.resize(n);
    c.model_xi_arcsec.resize(n);
  }
  if (c.has_truth) {
    c.truth_eta_arcsec.resize(n);
    c.truth_xi_arcsec.resize(n);
  }
  for (std::size_t k = 0; k < n; ++k) {
    const dov::Sample& s = samples[k];
    c.time_s[k] = s.time_s;
    c.lat_deg[k] = units::rad_to_deg(s.lat_rad);
    c.lon_deg[k] = units::rad_to_deg(s.lon_rad);
    c.height_m[k] = s.height_m;
    c.speed_m_s[k] = s.speed_m_s;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        c.lgu_body_to_nav[9 * k + 3 * i + j] = s.lgu_body_to_nav(i, j);
        c.ins_body_to_nav[9 * k + 3 * i + j] = s.ins_body_to_nav(i, j);
      }
    if (model) {
      c.model_eta_arcsec[k] = units::rad_to_arcsec(s.model_eta_rad);
      c.model_xi_arcsec[k] = units::rad_to_arcsec(s.model_xi_rad);
    }
    if (c.has_truth) {
      c.truth_eta_arcsec[k] = units::rad_to_arcsec(truth[k].eta_rad);
      c.truth_xi_arcsec[k] = units::rad_to_arcsec(truth[k].xi_rad);
    }
  }
  return c;
}

namespace {

// All columns of one length n, the matrices 9n numbers.
void check_lengths(const DovLineColumns& line) {
  const std::size_t n = line.time_s.size();
  const auto one_length = [&](std::initializer_list<const std::vector<double>*> columns) {
    for (const auto* c : columns)
      if (c->size() != n)
        throw InputError("the line's arrays must have one length", {"", std::nullopt, "line"});
  };
  one_length({&line.lat_deg, &line.lon_deg, &line.height_m, &line.speed_m_s,
              &line.model_eta_arcsec, &line.model_xi_arcsec});
  for (const auto& [m, name] : {std::pair{&line.lgu_body_to_nav, "lgu_body_to_nav"},
                                std::pair{&line.ins_body_to_nav, "ins_body_to_nav"}})
    if (m->size() != 9 * n)
      throw InputError("must have the shape (n, 3, 3)", {"", std::nullopt, name});
  if (line.has_truth) one_length({&line.truth_eta_arcsec, &line.truth_xi_arcsec});
}

}  // namespace

dov::Input dov_input(const DovLineColumns& line) {
  check_lengths(line);
  const std::size_t n = line.time_s.size();
  dov::Input in;
  in.samples.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    dov::Sample& s = in.samples[k];
    s.time_s = line.time_s[k];
    s.lat_rad = units::deg_to_rad(line.lat_deg[k]);
    s.lon_rad = units::deg_to_rad(line.lon_deg[k]);
    s.height_m = line.height_m[k];
    s.speed_m_s = line.speed_m_s[k];
    s.model_eta_rad = units::arcsec_to_rad(line.model_eta_arcsec[k]);
    s.model_xi_rad = units::arcsec_to_rad(line.model_xi_arcsec[k]);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        s.lgu_body_to_nav(i, j) = line.lgu_body_to_nav[9 * k + 3 * i + j];
        s.ins_body_to_nav(i, j) = line.ins_body_to_nav[9 * k + 3 * i + j];
      }
  }
  if (line.has_truth) {
    in.truth.resize(n);
    for (std::size_t k = 0; k < n; ++k)
      in.truth[k] = {units::arcsec_to_rad(line.truth_eta_arcsec[k]),
                     units::arcsec_to_rad(line.truth_xi_arcsec[k]), {}};
  }
  return in;
}

}  // namespace meridian::io
