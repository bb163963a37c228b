#include "meridian/report/dov_outputs.hpp"

#include <iterator>

#include <fmt/format.h>

#include "meridian/core/units.hpp"

namespace meridian::report {
namespace {

using nlohmann::json;
double deg_h(double rad_s) { return rad_s / units::kDegree * 3600.0; }
json eta_xi(const dov::EtaXi& v) {
  return {{"eta", units::rad_to_arcsec(v.eta_rad)}, {"xi", units::rad_to_arcsec(v.xi_rad)}};
}

}  // namespace

json dov_summary_to_json(const dov::Result& r, const dov::Options& o) {
  const dov::Summary& s = r.summary;
  json j = {{"epochs", s.epochs},
            {"statistics_epochs", s.statistics_epochs},
            {"discretisations", s.discretisations},
            {"rejected", s.rejected},
            {"mean_sigma_arcsec",
             {{"filtered", eta_xi(s.rms_sigma_filtered)}, {"smoothed", eta_xi(s.rms_sigma_smoothed)}}},
            {"nis",
             {{"mean", s.mean_nis}, {"lower_95", s.nis_interval.lower}, {"upper_95", s.nis_interval.upper}}},
            {"eps_u_deg_per_h", {{"value", deg_h(s.eps_u_rad_s)}, {"sigma", deg_h(s.sigma_eps_u_rad_s)}}},
            {"discretisation", o.discretisation == dov::DiscretisationMethod::Exact
                                   ? "exact"
                                   : "published_first_order"},
            {"extraction", o.extraction == dov::Extraction::Exact ? "exact" : "skew_symmetric"},
            {"transport_rate",
             o.transport_rate ? json{{"baseline_s", o.transport_rate_baseline_s},
                                     {"updates", s.transport_rate_updates}}
                              : json(nullptr)},
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

std::string dov_summary_text(const dov::Result& r, const dov::Options& o) {
  const dov::Summary& s = r.summary;
  std::string t = fmt::format("epochs: {} (statistics over {})\n", s.epochs, s.statistics_epochs);
  t += fmt::format(
      "model: sigma_model {}\", zeta {}, correlation length {} m; r: east {}\", north {}\"; "
      "discretisation {}, extraction {}\n",
      units::rad_to_arcsec(o.model.sigma_model_rad), o.model.zeta, o.model.correlation_length_m,
      units::rad_to_arcsec(o.sigma_obs_east_rad), units::rad_to_arcsec(o.sigma_obs_north_rad),
      o.discretisation == dov::DiscretisationMethod::Exact ? "exact" : "published_first_order",
      o.extraction == dov::Extraction::Exact ? "exact" : "skew_symmetric");
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
  t += fmt::format("eps_U = {:.5f} ± {:.5f} °/h (smoothed)\n", deg_h(s.eps_u_rad_s),
                   deg_h(s.sigma_eps_u_rad_s));
  for (const std::string& n : r.notes) t += "note: " + n + "\n";
  for (const std::string& w : r.warnings) t += "warning: " + w + "\n";
  return t;
}

std::string dov_profile_csv_header(bool truth) {
  std::string h =
      "time_s,lat_deg,lon_deg,model_eta_arcsec,model_xi_arcsec,filtered_eta_arcsec,"
      "filtered_xi_arcsec,filtered_sigma_eta_arcsec,filtered_sigma_xi_arcsec,smoothed_eta_arcsec,"
      "smoothed_xi_arcsec,smoothed_sigma_eta_arcsec,smoothed_sigma_xi_arcsec,"
      "filtered_eps_u_deg_per_h,innovation_east_arcsec,innovation_north_arcsec,nis,accepted";
  if (truth) h += ",truth_eta_arcsec,truth_xi_arcsec";
  return h + "\n";
}

void append_dov_profile_line(std::string& out, const dov::EpochResult& e) {
  const auto as = [](double rad) { return units::rad_to_arcsec(rad); };
  fmt::format_to(std::back_inserter(out),
                 "{:.10g},{:.10f},{:.10f},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},"
                 "{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{}",
                 e.time_s, e.lat_rad / units::kDegree, e.lon_rad / units::kDegree,
                 as(e.model_eta_rad), as(e.model_xi_rad), as(e.filtered.eta_rad),
                 as(e.filtered.xi_rad), as(e.filtered.sigma_eta_rad), as(e.filtered.sigma_xi_rad),
                 as(e.smoothed.eta_rad), as(e.smoothed.xi_rad), as(e.smoothed.sigma_eta_rad),
                 as(e.smoothed.sigma_xi_rad), deg_h(e.filtered.eps_u_rad_s),
                 as(e.innovation_east_rad), as(e.innovation_north_rad), e.nis,
                 e.accepted ? 1 : 0);
  if (e.truth)
    fmt::format_to(std::back_inserter(out), ",{:.10g},{:.10g}", as(e.truth->eta_rad),
                   as(e.truth->xi_rad));
  out += '\n';
}

}  // namespace meridian::report
