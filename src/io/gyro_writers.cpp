#include "meridian/io/gyro_writers.hpp"

#include <cmath>
#include <sstream>

#include <fmt/format.h>

#include "meridian/core/dms.hpp"
#include "meridian/core/units.hpp"
#include "gyro_record.hpp"

namespace meridian::io {
namespace {

constexpr double kArcsec = units::kArcsecond;

std::string q(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}
std::string dms(double rad) { return q(format_dms(Angle::radians(rad), {4, false, false})); }
std::string num(double v) { return fmt::format("{}", v); }
std::string list(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + num(v[i]);
  return s + "]";
}
std::string comment_block(const std::string& header) {
  std::string out;
  std::istringstream in(header);
  std::string line;
  while (std::getline(in, line)) out += "# " + line + "\n";
  return out;
}

void instrument_yaml(std::string& o, const gyro::InstrumentSpec& s) {
  o += "instrument:\n";
  if (!s.name.empty()) o += "  name: " + q(s.name) + "\n";
  if (!s.serial.empty()) o += "  serial: " + q(s.serial) + "\n";
  o += "  scale_value_arcsec: " + num(s.scale_value_rad / kArcsec) + "\n";
  if (s.sigma_scale_value_rad > 0) o += "  scale_value_sigma_arcsec: " + num(s.sigma_scale_value_rad / kArcsec) + "\n";
  if (s.torsion_ratio) {
    o += "  torsion_ratio: " + num(s.torsion_ratio->value) + "\n";
    if (s.torsion_ratio->sigma > 0) o += "  torsion_ratio_sigma: " + num(s.torsion_ratio->sigma) + "\n";
  }
  if (s.tracking_period_s || s.nontracking_period_s || s.free_period_s) {
    o += "  periods:\n";
    double sig = 0;
    if (s.tracking_period_s) o += "    tracking_s: " + num(s.tracking_period_s->value) + "\n", sig = s.tracking_period_s->sigma;
    if (s.nontracking_period_s) o += "    nontracking_s: " + num(s.nontracking_period_s->value) + "\n";
    if (s.free_period_s) o += "    free_s: " + num(s.free_period_s->value) + "\n";
    if (sig > 0) o += "    sigma_s: " + num(sig) + "\n";
  }
  if (s.constants_latitude_rad) o += "  constants_latitude_deg: " + num(*s.constants_latitude_rad / units::kDegree) + "\n";
  if (s.transit_factor_rad_per_div_s) {
    o += "  transit_factor_arcsec_per_div_s: " + num(s.transit_factor_rad_per_div_s->value / kArcsec) + "\n";
    if (s.transit_factor_rad_per_div_s->sigma > 0)
      o += "  transit_factor_sigma_arcsec_per_div_s: " + num(s.transit_factor_rad_per_div_s->sigma / kArcsec) + "\n";
  }
  o += "  sigma_time_s: " + num(s.sigma_time_s) + "\n";
  o += "  sigma_reading_div: " + num(s.sigma_reading_div) + "\n";
  o += "  accuracy_class_arcsec: " + num(s.accuracy_class_arcsec) + "\n";
}

void determination_yaml(std::string& o, const gyro::DeterminationInput& d, const std::string& ind) {
  // `ind` is the indentation of the list item's dash.
  const std::string in = ind + "  ";
  o += ind + "- mode: " + gyro::to_string(d.mode) + "\n";
  if (!d.label.empty()) o += in + "label: " + q(d.label) + "\n";
  if (!d.time.empty()) o += in + "time: " + q(d.time) + "\n";
  if (!d.observer.empty()) o += in + "observer: " + q(d.observer) + "\n";
  o += in + "method: " + gyro::method_request_name(d.method) + "\n";
  if (d.mode == gyro::Mode::Tracking) {
    o += in + "reversals: [";
    for (std::size_t i = 0; i < d.tracking.reversals_rad.size(); ++i)
      o += (i ? ", " : "") + dms(d.tracking.reversals_rad[i]);
    o += "]\n";
    if (std::isfinite(d.tracking.sigma_reading_rad))
      o += in + "sigma_reading_arcsec: " + num(d.tracking.sigma_reading_rad / kArcsec) + "\n";
  } else {
    const auto& n = d.nontracking;
    o += in + "clamp_reading: " + dms(d.clamp_reading_rad) + "\n";
    if (n.period_s) {
      o += in + "period_s: " + num(n.period_s->value) + "\n";
      if (n.period_s->sigma > 0) o += in + "period_sigma_s: " + num(n.period_s->sigma) + "\n";
    }
    o += in + "sigma_time_s: " + num(n.sigma_time_s) + "\n";
    o += in + "sigma_reading_div: " + num(n.sigma_reading_div) + "\n";
    if (!n.crossings.empty()) {
      o += in + "crossings:\n";
      for (const auto& c : n.crossings)
        o += in + "  - {level_div: " + num(c.level_div) + ", first_direction: " +
             (c.first_direction > 0 ? "east" : "west") + ", times_s: " + list(c.times_s) + "}\n";
    }
    if (!n.reversals_div.empty()) o += in + "reversals_div: " + list(n.reversals_div) + "\n";
    if (!n.reversal_times_s.empty()) o += in + "reversal_times_s: " + list(n.reversal_times_s) + "\n";
  }
  if (d.zero_position && !d.zero_before && !d.zero_after) {
    o += in + "zero_position_div: " + num(d.zero_position->value) + "\n";
    if (d.zero_position->sigma > 0) o += in + "zero_position_sigma_div: " + num(d.zero_position->sigma) + "\n";
  }
  if (d.zero_before || d.zero_after) {
    o += in + "zero_position:\n";
    auto run = [&](const char* name, const gyro::ZeroPositionRun& r) {
      o += in + "  " + name + ": {reversals_div: " + list(r.reversals_div);
      if (!r.times_s.empty()) o += ", times_s: " + list(r.times_s);
      o += "}\n";
    };
    if (d.zero_before) run("before", *d.zero_before);
    if (d.zero_after) run("after", *d.zero_after);
  }
  if (d.target_reading_rad) {
    o += in + "target_reading: " + dms(d.target_reading_rad->value) + "\n";
    if (d.target_reading_rad->sigma > 0)
      o += in + "target_sigma_arcsec: " + num(d.target_reading_rad->sigma / kArcsec) + "\n";
  }
  if (!d.target_rounds.empty()) {
    o += in + "target_rounds:\n";
    for (const auto& r : d.target_rounds)
      o += in + "  - {when: " + (r.when == gyro::TargetRound::When::Before ? "before" : "after") +
           ", left: " + dms(r.face_left_rad) + ", right: " + dms(r.face_right_rad) + "}\n";
    if (!d.target_reading_rad && d.target_round_sigma_rad > 0)
      o += in + "target_sigma_arcsec: " + num(d.target_round_sigma_rad / kArcsec) + "\n";
  }
}

void record_yaml(std::string& o, const gyro::RecordSheet& r) {
  std::string body;
  for (const auto& [key, value] : detail::record_fields(r))
    if (!value->empty()) body += std::string("  ") + key + ": " + q(*value) + "\n";
  if (!body.empty()) o += "record:\n" + body;
}

void point_yaml(std::string& o, const char* key, const gyro::PointInput& p, const std::string& ind) {
  o += ind + key + ":\n";
  const std::string in = ind + "  ";
  if (!p.name.empty()) o += in + "name: " + q(p.name) + "\n";
  if (p.x_north_m) o += in + "x_m: " + num(*p.x_north_m) + "\n";
  if (p.y_east_m) o += in + "y_m: " + num(*p.y_east_m) + "\n";
  if (p.lat_rad) o += in + "latitude_deg: " + dms(*p.lat_rad) + "\n";
  if (p.lon_rad) o += in + "longitude_deg: " + dms(*p.lon_rad) + "\n";
  if (p.eta_rad) {
    o += in + "eta_arcsec: " + num(p.eta_rad->value / kArcsec) + "\n";
    if (p.eta_rad->sigma > 0) o += in + "eta_sigma_arcsec: " + num(p.eta_rad->sigma / kArcsec) + "\n";
  }
  if (p.height_m) o += in + "height_m: " + num(*p.height_m) + "\n";
  if (p.xi_rad) {
    o += in + "xi_arcsec: " + num(p.xi_rad->value / kArcsec) + "\n";
    if (p.xi_rad->sigma > 0) o += in + "xi_sigma_arcsec: " + num(p.xi_rad->sigma / kArcsec) + "\n";
  }
}

std::string grid_system(const geodesy::GridDefinition& g) {
  switch (g.system) {
    case geodesy::ZoneSystem::GaussKruger3: return "gk3";
    case geodesy::ZoneSystem::GaussKruger6: return "gk6";
    case geodesy::ZoneSystem::UTM: return "utm";
    case geodesy::ZoneSystem::Custom: return "custom";
  }
  return "custom";
}

}  // namespace

std::string reduce_file_yaml(const gyro::ReduceInput& in, const std::string& header) {
  std::string o = comment_block(header);
  instrument_yaml(o, in.instrument);
  o += "station:\n  latitude_deg: " + num(in.latitude_rad / units::kDegree) + "\n";
  o += "determinations:\n";
  for (const auto& d : in.determinations) determination_yaml(o, d, "  ");
  return o;
}

std::string campaign_file_yaml(const gyro::CampaignInput& c, const std::string& header) {
  std::string o = comment_block(header);
  if (!c.name.empty()) o += "campaign: " + q(c.name) + "\n";
  record_yaml(o, c.record);
  instrument_yaml(o, c.instrument);
  const auto& g = c.grid;
  o += "grid:\n  system: " + grid_system(g) + "\n";
  if (g.system == geodesy::ZoneSystem::Custom) {
    o += "  central_meridian_deg: " + num(g.central_meridian_rad / units::kDegree) + "\n";
    o += "  scale_factor: " + num(g.scale_factor) + "\n";
    o += "  false_easting_m: " + num(g.false_easting_m) + "\n";
    o += "  false_northing_m: " + num(g.false_northing_m) + "\n";
  } else {
    o += "  zone: " + num(g.zone) + "\n";
  }
  if (g.system == geodesy::ZoneSystem::UTM) o += std::string("  hemisphere: ") + (g.north ? "north" : "south") + "\n";
  if (g.zone_prefix) o += "  zone_prefix: true\n";
  o += "  ellipsoid: " + g.ellipsoid.name + "\n";
  if (c.known_line) {
    const auto& k = *c.known_line;
    o += "known_line:\n";
    point_yaml(o, "from", k.from, "  ");
    if (k.to) point_yaml(o, "to", *k.to, "  ");
    if (k.zenith_angle_rad) o += "  zenith_angle: " + dms(*k.zenith_angle_rad) + "\n";
    o += "  azimuth: {kind: " + geodesy::to_string(k.azimuth.kind) + ", value: " + dms(k.azimuth.value_rad.value) +
         ", sigma_arcsec: " + num(k.azimuth.value_rad.sigma / kArcsec) + "}\n";
    if (!k.before.empty()) {
      o += "  before:\n";
      for (const auto& d : k.before) determination_yaml(o, d, "    ");
    }
    if (!k.after.empty()) {
      o += "  after:\n";
      for (const auto& d : k.after) determination_yaml(o, d, "    ");
    }
  }
  if (c.instrument_constant_rad)
    o += "instrument_constant: {value: " + dms(c.instrument_constant_rad->value) +
         ", sigma_arcsec: " + num(c.instrument_constant_rad->sigma / kArcsec) + "}\n";
  o += "line:\n";
  point_yaml(o, "from", c.line.from, "  ");
  if (c.line.to) point_yaml(o, "to", *c.line.to, "  ");
  if (c.line.zenith_angle_rad) o += "  zenith_angle: " + dms(*c.line.zenith_angle_rad) + "\n";
  o += "  determinations:\n";
  for (const auto& d : c.line.determinations) determination_yaml(o, d, "    ");
  const gyro::Tolerances& t = c.tolerances;
  std::string tol;
  auto arcsec = [&](const char* key, const std::optional<double>& v) {
    if (v) tol += std::string("  ") + key + ": " + num(*v / kArcsec) + "\n";
  };
  auto div = [&](const char* key, const std::optional<double>& v) {
    if (v) tol += std::string("  ") + key + ": " + num(*v) + "\n";
  };
  arcsec("determination_difference_arcsec", t.determination_difference_rad);
  arcsec("instrument_constant_difference_arcsec", t.instrument_constant_difference_rad);
  arcsec("instrument_constant_means_arcsec", t.instrument_constant_means_rad);
  arcsec("orientation_difference_arcsec", t.orientation_difference_rad);
  arcsec("orientation_mean_sigma_arcsec", t.orientation_mean_sigma_rad);
  div("zero_position_div", t.zero_position_div);
  div("zero_position_limit_div", t.zero_position_limit_div);
  arcsec("known_azimuth_coordinates_arcsec", t.known_azimuth_coordinates_rad);
  arcsec("instrument_constant_max_arcsec", t.instrument_constant_max_rad);
  if (!tol.empty()) o += "tolerances:\n" + tol;
  if (c.gravity_model)
    o += "gravity_model: {model: " + q(c.gravity_model->source) +
         (c.gravity_model->max_degree >= 0 ? ", max_degree: " + std::to_string(c.gravity_model->max_degree) : "") +
         ", eta_sigma_arcsec: " + num(c.gravity_model->sigma_eta_rad / kArcsec) +
         ", xi_sigma_arcsec: " + num(c.gravity_model->sigma_xi_rad / kArcsec) + "}\n";
  return o;
}

}  // namespace meridian::io
