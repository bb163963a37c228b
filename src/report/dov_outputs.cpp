#include "meridian/report/dov_outputs.hpp"

#include <iterator>
#include <limits>

#include <fmt/format.h>

#include "meridian/core/units.hpp"

namespace meridian::report {
namespace {

using nlohmann::json;
double deg_h(double rad_s) { return rad_s / units::kDegree * 3600.0; }
json eta_xi(const dov::EtaXi& v) {
  return {{"eta", units::rad_to_arcsec(v.eta_rad)}, {"xi", units::rad_to_arcsec(v.xi_rad)}};
}
const char* discretisation_name(const dov::Options& o) {
  return o.discretisation == dov::DiscretisationMethod::Exact ? "exact" : "published_first_order";
}
const char* extraction_name(const dov::Options& o) {
  return o.extraction == dov::Extraction::Exact ? "exact" : "skew_symmetric";
}

// The Ljung–Box test; null when there were too few epochs to test.
json whiteness_json(const filter::LjungBoxResult& w) {
  if (w.lags == 0) return nullptr;
  return {{"test", "ljung_box"}, {"q", w.q},           {"dof", w.dof},
          {"lags", w.lags},      {"alpha", w.alpha},   {"critical_value", w.critical_value},
          {"p_value", w.p_value}, {"pass", w.pass},    {"samples", w.samples}};
}

}  // namespace

json dov_summary_to_json(const dov::Result& r) {
  const dov::Summary& s = r.summary;
  const dov::Options& o = r.options;
  json j = {{"epochs", s.epochs},
            {"statistics_epochs", s.statistics_epochs},
            {"discretisations", s.discretisations},
            {"rejected", s.rejected},
            {"mean_sigma_arcsec",
             {{"filtered", eta_xi(s.rms_sigma_filtered)}, {"smoothed", eta_xi(s.rms_sigma_smoothed)}}},
            {"nis",
             {{"mean", s.mean_nis}, {"lower_95", s.nis_interval.lower}, {"upper_95", s.nis_interval.upper}}},
            {"eps_u_deg_per_h", {{"value", deg_h(s.eps_u_rad_s)}, {"sigma", deg_h(s.sigma_eps_u_rad_s)}}},
            {"discretisation", discretisation_name(o)},
            {"extraction", extraction_name(o)},
            {"transport_rate",
             o.transport_rate ? json{{"baseline_s", o.transport_rate_baseline_s},
                                     {"updates", s.transport_rate_updates}}
                              : json(nullptr)},
            {"stationary",
             {{"threshold_m_s", s.stationary_speed_m_s},
              {"threshold_from", s.stationary_from_speed_sigma ? "speed_sigma_m_s" : "stationary_speed_m_s"},
              {"min_duration_s", o.stationary_min_duration_s},
              {"steps", s.stationary_steps},
              {"reference_speed_m_s", s.reference_speed_m_s}}},
            {"whiteness", whiteness_json(s.whiteness)},
            {"notes", r.notes},
            {"warnings", r.warnings}};
  if (s.rms_model)
    j["rms_arcsec"] = {{"model", eta_xi(*s.rms_model)},
                       {"filtered", eta_xi(*s.rms_filtered)},
                       {"smoothed", eta_xi(*s.rms_smoothed)}};
  if (s.mean_nees_filtered)
    j["nees"] = {{"filtered", *s.mean_nees_filtered}, {"smoothed", *s.mean_nees_smoothed}};
  return j;
}

std::string dov_summary_text(const dov::Result& r) {
  const dov::Summary& s = r.summary;
  const dov::Options& o = r.options;
  std::string t = fmt::format("epochs: {} (statistics over {})\n", s.epochs, s.statistics_epochs);
  t += fmt::format(
      "model: sigma_model {}\", zeta {}, correlation length {} m; r: east {}\", north {}\"; "
      "discretisation {}, extraction {}\n",
      units::rad_to_arcsec(o.model.sigma_model_rad), o.model.zeta, o.model.correlation_length_m,
      units::rad_to_arcsec(o.sigma_obs_east_rad), units::rad_to_arcsec(o.sigma_obs_north_rad),
      discretisation_name(o), extraction_name(o));
  if (o.transport_rate)
    t += fmt::format("attitude dynamics: Earth rate + transport rate from the track ({} s "
                     "baselines, {} closed)\n",
                     o.transport_rate_baseline_s, s.transport_rate_updates);
  else
    t += "attitude dynamics: Earth rate only (transport_rate: false)\n";
  if (s.rms_model)
    t += fmt::format(
        "RMS error (″)       eta      xi\n  model     {:9.4f} {:7.4f}\n  filtered  {:9.4f} "
        "{:7.4f}\n  smoothed  {:9.4f} {:7.4f}\n",
        units::rad_to_arcsec(s.rms_model->eta_rad), units::rad_to_arcsec(s.rms_model->xi_rad),
        units::rad_to_arcsec(s.rms_filtered->eta_rad), units::rad_to_arcsec(s.rms_filtered->xi_rad),
        units::rad_to_arcsec(s.rms_smoothed->eta_rad),
        units::rad_to_arcsec(s.rms_smoothed->xi_rad));
  t += fmt::format(
      "quadratic-mean σ (″): filtered eta {:.4f} xi {:.4f}; smoothed eta {:.4f} xi {:.4f}\n",
      units::rad_to_arcsec(s.rms_sigma_filtered.eta_rad),
      units::rad_to_arcsec(s.rms_sigma_filtered.xi_rad),
      units::rad_to_arcsec(s.rms_sigma_smoothed.eta_rad),
      units::rad_to_arcsec(s.rms_sigma_smoothed.xi_rad));
  t += fmt::format("mean NIS {:.3f} (95 % interval [{:.3f}, {:.3f}]), {} rejected\n", s.mean_nis,
                   s.nis_interval.lower, s.nis_interval.upper, s.rejected);
  if (s.whiteness.lags > 0)
    t += fmt::format("innovation whiteness: Ljung–Box Q {:.1f}, critical {:.1f} (χ²({:g}), {} lags, "
                     "alpha {:g}), p = {:.3g}: {}\n",
                     s.whiteness.q, s.whiteness.critical_value, s.whiteness.dof, s.whiteness.lags,
                     s.whiteness.alpha, s.whiteness.p_value, s.whiteness.pass ? "white" : "NOT white");
  else
    t += "innovation whiteness: not tested (fewer than 5 epochs)\n";
  t += fmt::format("stationary below {:g} m/s ({}) held for {:g} s: {} of {} steps; P0 reference "
                   "speed {:.4g} m/s\n",
                   s.stationary_speed_m_s,
                   s.stationary_from_speed_sigma ? "stationary_sigma_factor x speed_sigma_m_s"
                                                 : "stationary_speed_m_s",
                   o.stationary_min_duration_s, s.stationary_steps,
                   s.epochs > 0 ? s.epochs - 1 : 0, s.reference_speed_m_s);
  t += fmt::format("eps_U = {:.5f} ± {:.5f} °/h (smoothed)\n", deg_h(s.eps_u_rad_s),
                   deg_h(s.sigma_eps_u_rad_s));
  for (const std::string& n : r.notes) t += "note: " + n + "\n";
  for (const std::string& w : r.warnings) t += "warning: " + w + "\n";
  return t;
}

const std::array<const char*, kDovProfileColumns>& dov_profile_columns() {
  static constexpr std::array<const char*, kDovProfileColumns> kNames = {
      "time_s",
      "lat_deg",
      "lon_deg",
      "model_eta_arcsec",
      "model_xi_arcsec",
      "filtered_eta_arcsec",
      "filtered_xi_arcsec",
      "filtered_sigma_eta_arcsec",
      "filtered_sigma_xi_arcsec",
      "smoothed_eta_arcsec",
      "smoothed_xi_arcsec",
      "smoothed_sigma_eta_arcsec",
      "smoothed_sigma_xi_arcsec",
      "filtered_eps_u_deg_per_h",
      "innovation_east_arcsec",
      "innovation_north_arcsec",
      "nis",
      "accepted",
      "truth_eta_arcsec",
      "truth_xi_arcsec"};
  return kNames;
}

std::size_t dov_profile_column_count(bool truth) {
  return truth ? kDovProfileColumns : kDovProfileColumns - 2;
}

std::array<double, kDovProfileColumns> dov_profile_values(const dov::EpochResult& e) {
  const auto as = [](double rad) { return units::rad_to_arcsec(rad); };
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  return {e.time_s,
          e.lat_rad / units::kDegree,
          e.lon_rad / units::kDegree,
          as(e.model_eta_rad),
          as(e.model_xi_rad),
          as(e.filtered.eta_rad),
          as(e.filtered.xi_rad),
          as(e.filtered.sigma_eta_rad),
          as(e.filtered.sigma_xi_rad),
          as(e.smoothed.eta_rad),
          as(e.smoothed.xi_rad),
          as(e.smoothed.sigma_eta_rad),
          as(e.smoothed.sigma_xi_rad),
          deg_h(e.filtered.eps_u_rad_s),
          as(e.innovation_east_rad),
          as(e.innovation_north_rad),
          e.nis,
          e.accepted ? 1.0 : 0.0,
          e.truth ? as(e.truth->eta_rad) : nan,
          e.truth ? as(e.truth->xi_rad) : nan};
}

std::string dov_profile_csv_header(bool truth) {
  std::string h;
  const auto& names = dov_profile_columns();
  for (std::size_t i = 0; i < dov_profile_column_count(truth); ++i)
    h += (i == 0 ? "" : ",") + std::string(names[i]);
  return h + "\n";
}

void append_dov_profile_line(std::string& out, const dov::EpochResult& e) {
  const std::array<double, kDovProfileColumns> v = dov_profile_values(e);
  fmt::format_to(std::back_inserter(out),
                 "{:.10g},{:.10f},{:.10f},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},"
                 "{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{}",
                 v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], v[11], v[12],
                 v[13], v[14], v[15], v[16], static_cast<int>(v[17]));
  if (e.truth) fmt::format_to(std::back_inserter(out), ",{:.10g},{:.10g}", v[18], v[19]);
  out += '\n';
}

void DovProfileCsv::add(const dov::EpochResult& e) {
  if (!header_) {
    text_ += dov_profile_csv_header(e.truth.has_value());
    header_ = true;
  }
  append_dov_profile_line(text_, e);
}

}  // namespace meridian::report
