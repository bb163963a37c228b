#include "meridian/report/gyro_json.hpp"

#include <cmath>

#include "json_number.hpp"
#include "meridian/core/dms.hpp"
#include "meridian/core/units.hpp"

namespace meridian::report {
namespace {

using nlohmann::json;

using detail::json_number;
json arcsec(double rad) { return json_number(rad / units::kArcsecond); }
json uncertain(const gyro::Uncertain& u, double scale = 1.0) {
  return {{"value", json_number(u.value / scale)}, {"sigma", json_number(u.sigma / scale)}};
}
json strings(const std::vector<std::string>& v) { return json(v); }

json reversal_json(const gyro::ReversalResult& r, bool radians) {
  const double s = radians ? units::kArcsecond : 1.0;
  json j;
  j["unit"] = radians ? "arcsec" : "div";
  j["centre"] = radians ? json{{"value_deg", json_number(r.centre.value / units::kDegree)},
                               {"sigma_arcsec", json_number(r.centre.sigma / units::kArcsecond)}}
                        : uncertain(r.centre);
  if (r.amplitude) j["amplitude"] = uncertain(*r.amplitude, s);
  if (r.damping) j["damping"] = r.method == gyro::ReversalMethod::NonlinearLsq
                                    ? uncertain(*r.damping)
                                    : uncertain(*r.damping, s);
  j["cofactor_centre"] = json_number(r.cofactor_centre);
  j["dof"] = r.dof;
  j["sigma0"] = json_number(r.sigma0 / s);
  j["sigma_is_aposteriori"] = r.sigma_is_aposteriori;
  json res = json::array();
  for (double v : r.residuals) res.push_back(json_number(v / s));
  j["residuals"] = res;
  if (!r.partial_means.empty()) {
    json pm = json::array();
    for (double v : r.partial_means)
      pm.push_back(radians ? json_number(v / units::kDegree) : json_number(v));
    j["partial_means"] = pm;
  }
  j["notes"] = strings(r.notes);
  return j;
}

json az(const gyro::Uncertain& u) {
  return json{{"deg", json_number(u.value / units::kDegree)},
              {"dms", format_direction_dms(Angle::radians(u.value), {2, true, false})},
              {"sigma_arcsec", json_number(u.sigma / units::kArcsecond)}};
}

json checks_json(const std::vector<gyro::Check>& checks) {
  json a = json::array();
  for (const auto& k : checks)
    a.push_back({{"name", k.name},
                 {"value", json_number(k.value)},
                 {"tolerance", json_number(k.tolerance)},
                 {"unit", gyro::to_string(k.unit)},
                 {"pass", k.pass},
                 {"minimum", k.minimum},
                 {"signed_value", k.signed_value},
                 {"source", k.source},
                 {"field", k.field}});
  return a;
}

}  // namespace

json method_to_json(const gyro::MethodResult& r, gyro::Mode mode) {
  json j;
  j["method"] = gyro::to_string(r.method);
  j["north_reading_deg"] = json_number(r.north.north_rad / units::kDegree);
  j["north_reading_dms"] = format_direction_dms(Angle::radians(r.north.north_rad), {2, true, false});
  j["sigma_arcsec"] = arcsec(r.north.sigma_rad);
  j["zero_position_correction_arcsec"] = arcsec(r.north.zero_correction_rad);
  if (mode == gyro::Mode::NonTracking) {
    j["delta_n_arcsec"] = arcsec(r.north.delta_n_rad);
    if (r.beta) {
      const auto& b = *r.beta;
      j["beta_div"] = json_number(b.beta_div.value);
      j["beta_sigma_div"] = json_number(b.beta_div.sigma);
      j["approximation_error_div"] = json_number(b.approximation_error_div);
      j["approximation_error_arcsec"] = arcsec(r.approximation_error_rad);
      if (b.amplitude_div) j["amplitude_div"] = uncertain(*b.amplitude_div);
      if (b.period_s) j["period_s"] = uncertain(*b.period_s);
      if (b.transit_delta_n_rad)
        j["transit_delta_n_arcsec"] = uncertain(*b.transit_delta_n_rad, units::kArcsecond);
      j["warnings"] = strings(b.warnings);
      j["assumptions"] = strings(b.assumptions);
    }
    if (r.fit) {
      const auto& f = *r.fit;
      json fit;
      fit["t0_s"] = uncertain(f.t0_s);
      fit["damping_per_s"] = uncertain(f.damping_per_s);
      fit["sigma0"] = json_number(f.sigma0);
      fit["dof"] = f.dof;
      fit["iterations"] = f.iterations;
      json res = json::array();
      for (const auto& v : f.residuals)
        res.push_back(
            {{"kind", v.kind == gyro::UnifiedFitResidual::Kind::CrossingTime ? "crossing_time_s"
                                                                             : "reversal_div"},
             {"group", v.group},
             {"index", v.index},
             {"observed", json_number(v.observed)},
             {"residual", json_number(v.residual)},
             {"standardized", json_number(v.standardized)},
             {"redundancy", json_number(v.redundancy)}});
      fit["residuals"] = res;
      j["fit"] = fit;
    }
  } else if (r.reversal) {
    j["delta_n_arcsec"] = arcsec(r.north.delta_n_rad);
    j["fit"] = reversal_json(*r.reversal, true);
  }
  return j;
}

json determination_to_json(const gyro::DeterminationResult& r) {
  json j = method_to_json(r.primary, r.mode);
  j["mode"] = gyro::to_string(r.mode);
  j["method"] = gyro::method_request_name(r.method);
  if (!r.label.empty()) j["label"] = r.label;
  if (!r.method) {
    j["recommended_method"] = gyro::to_string(r.primary.method);
    json all = json::array();
    for (const auto& m : r.all) all.push_back(method_to_json(m, r.mode));
    j["results"] = all;
  }
  if (r.zero_position_used)
    j["zero_position_div"] = uncertain(*r.zero_position_used);
  else
    j["zero_position_div"] = nullptr;
  if (r.zero_position) {
    const auto& z = *r.zero_position;
    json zj;
    if (z.before) zj["before"] = reversal_json(z.before->fit, false);
    if (z.after) zj["after"] = reversal_json(z.after->fit, false);
    zj["mean_div"] = uncertain(z.mean_div);
    zj["difference_div"] = z.difference_div ? json_number(*z.difference_div) : json(nullptr);
    zj["tolerance_div"] = z.tolerance_div;
    zj["within_tolerance"] = z.within_tolerance;
    j["zero_position_runs"] = zj;
  }
  j["warnings"] = strings(r.warnings);
  return j;
}

json reduce_to_json(const gyro::ReduceResult& r) {
  json j;
  j["file"] = r.input.file;
  j["torsion_ratio"] = {{"value", r.instrument.instrument.torsion_ratio.value},
                        {"sigma", r.instrument.instrument.torsion_ratio.sigma}};
  j["notes"] = r.instrument.notes;
  j["determinations"] = json::array();
  for (const auto& d : r.determinations) j["determinations"].push_back(determination_to_json(d));
  return j;
}

json orientations_to_json(const gyro::OrientationsResult& r) {
  json j;
  j["station"] = r.station;
  j["target"] = r.target;
  j["grid_azimuths"] = json::array();
  for (const auto& t : r.grid_azimuths_rad) j["grid_azimuths"].push_back(az(t));
  j["mean_grid_azimuth"] = az(r.mean.mean);
  j["mean_grid_azimuth"]["sigma_propagated_arcsec"] = arcsec(r.mean.sigma_propagated);
  j["mean_grid_azimuth"]["sigma_empirical_arcsec"] = arcsec(r.mean.sigma_empirical);
  j["mean_grid_azimuth"]["sigma_own_arcsec"] = arcsec(r.sigma_own_propagated_rad);
  j["mean_grid_azimuth"]["sigma_shared_arcsec"] = arcsec(r.sigma_shared_rad);
  j["mean_grid_azimuth"]["sigma_if_independent_arcsec"] = arcsec(r.sigma_if_independent_rad);
  j["covariance_arcsec2"] = json::array();
  for (const auto& row : r.covariance_rad2) {
    json jr = json::array();
    for (double c : row) jr.push_back(c / (units::kArcsecond * units::kArcsecond));
    j["covariance_arcsec2"].push_back(jr);
  }
  j["shared_sources"] = strings(r.shared_sources);
  j["largest_difference_arcsec"] = arcsec(r.mean.max_difference);
  j["checks"] = checks_json(r.checks);
  j["all_checks_pass"] = r.all_checks_pass();
  j["limits_source"] = r.limits.source;
  j["notes"] = strings(r.notes);
  return j;
}

json transit_factor_to_json(const gyro::TransitFactorCalibration& c) {
  return {{"transit_factor_arcsec_per_div_s", c.factor_rad_per_div_s.value / units::kArcsecond},
          {"sigma_arcsec_per_div_s", c.factor_rad_per_div_s.sigma / units::kArcsecond},
          {"computed_arcsec_per_div_s", c.computed_rad_per_div_s / units::kArcsecond},
          {"amplitudes_div", {c.amplitude1_div.value, c.amplitude2_div.value}},
          {"time_differences_s", {c.dt1_s.value, c.dt2_s.value}},
          {"north_reading_deg", c.north_rad / units::kDegree},
          {"notes", c.notes}};
}

namespace {

// The stochastic model behind a determination's N_G (campaign option stochastic_model).
json stochastic_use_json(const gyro::StochasticUse& u) {
  json rho = json::array();
  for (double x : u.rho) rho.push_back(json_number(x));
  return {{"requested", gyro::to_string(u.requested)},
          {"used", u.used},
          {"fallback", u.fallback},
          {"reason", u.reason.empty() ? json(nullptr) : json(u.reason)},
          {"rho", rho},
          {"sigma1_arcsec", json_number(u.sigma1_arcsec)},
          {"sigma2_arcsec", json_number(u.sigma2_arcsec)}};
}

}  // namespace

json campaign_to_json(const gyro::CampaignResult& r) {
  auto point = [](const gyro::PointResult& p) {
    return json{{"name", p.name},
                {"latitude_deg", json_number(p.lat_rad / units::kDegree)},
                {"longitude_deg", json_number(p.lon_rad / units::kDegree)},
                {"x_m", json_number(p.grid.x_north_m)},
                {"y_m", json_number(p.grid.y_east_m)},
                {"convergence_arcsec", json_number(p.grid.convergence_rad / units::kArcsecond)},
                {"scale", json_number(p.grid.scale)}};
  };
  json j;
  j["campaign"] = r.name;
  j["stochastic_model"] = gyro::to_string(r.stochastic_model);
  j["record"] = {{"observer", r.record.observer},       {"booker", r.record.booker},
                 {"computed_by", r.record.computed_by}, {"checked_by", r.record.checked_by},
                 {"date", r.record.date},               {"weather", r.record.weather},
                 {"temperature", r.record.temperature}, {"remarks", r.record.remarks}};
  j["instrument"] = {{"name", r.instrument_name}, {"serial", r.instrument_serial}};
  j["station"] = point(r.station);
  if (r.target) j["target"] = point(*r.target);
  if (r.known_station) j["known_station"] = point(*r.known_station);
  j["torsion_ratio_station"] = uncertain(r.instrument_station.instrument.torsion_ratio);
  auto dets = [&](const std::vector<gyro::DeterminationResult>& d, const std::vector<gyro::Uncertain>& ag) {
    json a = json::array();
    for (std::size_t i = 0; i < d.size(); ++i) {
      json e = determination_to_json(d[i]);
      if (i < ag.size()) e["gyro_azimuth"] = az(ag[i]);
      e["stochastic_model"] = stochastic_use_json(d[i].stochastic);
      a.push_back(e);
    }
    return a;
  };
  if (r.instrument_constant) {
    const auto& e = *r.instrument_constant;
    json k;
    k["known_astronomic_azimuth"] = az(*r.known_astronomic_azimuth_rad);
    k["before"] = dets(r.known_before, r.known_gyro_azimuths_before);
    k["after"] = dets(r.known_after, r.known_gyro_azimuths_after);
    json eb = json::array(), ea = json::array();
    for (const auto& x : e.before) eb.push_back(uncertain(x, units::kArcsecond));
    for (const auto& x : e.after) ea.push_back(uncertain(x, units::kArcsecond));
    k["instrument_constants_before_arcsec"] = eb;
    k["instrument_constants_after_arcsec"] = ea;
    k["difference_arcsec"] = e.difference_rad ? arcsec(*e.difference_rad) : json(nullptr);
    j["calibration"] = k;
  }
  j["instrument_constant_arcsec"] = uncertain(r.instrument_constant_used_rad, units::kArcsecond);
  j["determinations"] = dets(r.determinations, r.gyro_azimuths);
  j["gyro_azimuth_mean"] = az(r.gyro_azimuth_mean.mean);
  j["gyro_azimuth_mean"]["sigma_propagated_arcsec"] = arcsec(r.gyro_azimuth_mean.sigma_propagated);
  j["gyro_azimuth_mean"]["sigma_empirical_arcsec"] = arcsec(r.gyro_azimuth_mean.sigma_empirical);
  const auto& c = r.chain;
  j["astronomic_azimuth"] = az(c.astronomic_azimuth_rad);
  j["laplace_correction_arcsec"] = c.laplace_applied ? arcsec(c.laplace_correction_rad) : json(nullptr);
  j["zenith_distance_term_arcsec"] = c.zenith_term_applied ? arcsec(c.zenith_correction_rad) : json(nullptr);
  j["zenith_distance_deg"] =
      c.zenith_distance_rad ? json_number(*c.zenith_distance_rad / units::kDegree) : json(nullptr);
  j["geodetic_azimuth"] = az(c.geodetic_azimuth_rad);
  j["convergence_arcsec"] = arcsec(c.convergence_rad);
  j["arc_to_chord_arcsec"] = c.arc_to_chord_applied ? arcsec(c.arc_to_chord_rad) : json(nullptr);
  j["grid_azimuth"] = az(c.grid_azimuth_rad);
  // The traverse's azimuth of the line from its coordinates, and gyro minus traverse.
  if (r.line_grid_azimuth_from_coordinates_rad) {
    j["grid_azimuth_from_coordinates_deg"] = json_number(*r.line_grid_azimuth_from_coordinates_rad / units::kDegree);
    j["gyro_minus_traverse_arcsec"] =
        arcsec(wrap_signed_rad(c.grid_azimuth_rad.value - *r.line_grid_azimuth_from_coordinates_rad));
  } else {
    j["grid_azimuth_from_coordinates_deg"] = nullptr;
    j["gyro_minus_traverse_arcsec"] = nullptr;
  }
  j["accuracy_class_arcsec"] = json_number(r.limits.accuracy_class_arcsec);
  j["accuracy_class_booked"] = r.input.instrument.accuracy_class_booked;
  j["checks"] = checks_json(r.checks);
  j["limits_source"] = r.limits.source;
  j["instrument_constant_one_run_sigma_arcsec"] =
      r.constant_one_run_sigma_rad ? arcsec(*r.constant_one_run_sigma_rad) : json(nullptr);
  j["line_one_run_sigma_arcsec"] = r.line_one_run_sigma_rad ? arcsec(*r.line_one_run_sigma_rad) : json(nullptr);
  j["all_checks_pass"] = r.all_checks_pass();
  j["notes"] = strings(r.notes);
  j["warnings"] = strings(r.warnings);
  return j;
}

}  // namespace meridian::report
