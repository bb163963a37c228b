#include "meridian/report/gyro_text.hpp"

#include <cmath>

#include <fmt/format.h>

#include "meridian/core/dms.hpp"
#include "meridian/core/units.hpp"
#include "meridian/report/format.hpp"

namespace meridian::report {
namespace {

void method_line(std::string& out, const gyro::MethodResult& m, const AngleFormat& f) {
  out += fmt::format("  {:<18} N_G {:>15}  sigma {:>7}\n", gyro::to_string(m.method), f.dir(m.north.north_rad),
                     f.sig(m.north.sigma_rad));
}

}  // namespace

std::string determination_text(const gyro::DeterminationResult& r, int index, const AngleFormat& f) {
  std::string out = fmt::format("Determination {}{} ({}, method {})\n", index + 1,
                                r.label.empty() ? "" : " \"" + r.label + "\"", gyro::to_string(r.mode),
                                gyro::method_request_name(r.method));
  auto line = [&](const gyro::MethodResult& m) {
    if (r.mode == gyro::Mode::NonTracking && m.beta) {
      out += fmt::format("  {:<18} beta {:+9.4f} div  dN {:>10}  N_G {:>15}  sigma {:>7}", gyro::to_string(m.method),
                         m.beta->beta_div.value, f.sec(m.north.delta_n_rad, 3), f.dir(m.north.north_rad, 2),
                         f.sig(m.north.sigma_rad));
      if (m.approximation_error_rad != 0.0)
        out += fmt::format("  approximation error {:+.3f}\"",
                           m.approximation_error_rad / units::kArcsecond);
      out += "\n";
    } else {
      method_line(out, m, f);
    }
  };
  if (!r.method) {
    for (const auto& m : r.all) line(m);
    out += fmt::format("  recommended: {}\n", gyro::to_string(r.primary.method));
  } else {
    line(r.primary);
  }
  if (r.zero_position_used)
    out += fmt::format("  zero position {:+.3f} div (sigma {:.3f}), correction {}\n",
                       r.zero_position_used->value, r.zero_position_used->sigma,
                       f.sec(r.primary.north.zero_correction_rad));
  for (const auto& w : r.warnings) out += "  warning: " + w + "\n";
  return out;
}

std::string check_statement(const gyro::Check& k) {
  const bool count = k.unit == gyro::CheckUnit::Runs || k.unit == gyro::CheckUnit::Observers ||
                     k.unit == gyro::CheckUnit::Checks || k.unit == gyro::CheckUnit::Entries;
  const int decimals = count ? 0 : k.unit == gyro::CheckUnit::Arcsec ? 1 : 2;
  const std::string unit = " " + gyro::to_string(k.unit);
  // An angle of a degree or more is read as D°M'S" (a round 180° off, a line booked the wrong way round).
  const std::string dms = k.unit == gyro::CheckUnit::Arcsec && std::fabs(k.value) >= 3600.0
                              ? " = " + format_dms(Angle::radians(k.value * units::kArcsecond))
                              : std::string();
  return fmt::format("{}: {:.{}f}{}{} ({} {}{:.{}f}{})", k.name, k.value, decimals, unit, dms,
                     k.minimum ? "at least" : "limit", k.signed_value ? "+-" : "", k.tolerance, decimals,
                     count ? "" : unit);
}

std::string check_text(const gyro::Check& k) {
  return std::string(k.pass ? "[PASS] " : "[FAIL] ") + check_statement(k);
}

std::string reduce_text(const gyro::ReduceResult& r, const AngleFormat& f) {
  const gyro::Instrument& inst = r.instrument.instrument;
  std::string out = fmt::format("{}: {} determination(s), lambda = {:.5f}, tau = {:.1f}\"/div\n",
                                r.input.file, r.determinations.size(), inst.torsion_ratio.value,
                                inst.scale_value_rad / units::kArcsecond);
  for (const auto& n : r.instrument.notes) out += "  note: " + n + "\n";
  for (std::size_t i = 0; i < r.determinations.size(); ++i)
    out += determination_text(r.determinations[i], static_cast<int>(i), f);
  return out;
}

std::string orientations_text(const gyro::OrientationsResult& r, const AngleFormat& f) {
  const std::vector<std::string>& files = r.files;
  std::string out = fmt::format("Independent orientations of the line {}-{}\n", r.station, r.target);
  for (std::size_t i = 0; i < r.grid_azimuths_rad.size(); ++i)
    out += fmt::format("  {}  T = {:>15}  sigma {:>6}  {}\n", i + 1, f.dir(r.grid_azimuths_rad[i].value),
                       f.sig(r.grid_azimuths_rad[i].sigma), i < files.size() ? files[i] : "");
  out += fmt::format("  mean T = {:>15}  sigma {}\n\nChecks (limits: {})\n", f.dir(r.mean.mean.value),
                     f.sig(r.mean.mean.sigma), r.limits.source);
  for (const auto& k : r.checks) out += "  " + check_text(k) + "\n";
  for (const auto& n : r.notes) out += "  - " + n + "\n";
  return out;
}

std::string transit_factor_text(const gyro::TransitFactorCalibration& c) {
  std::string out = fmt::format("transit factor c = {:.4f} \"/(div s)  sigma {:.4f}\n",
                                c.factor_rad_per_div_s.value / units::kArcsecond,
                                c.factor_rad_per_div_s.sigma / units::kArcsecond);
  if (c.computed_rad_per_div_s > 0)
    out += fmt::format("computed (1+lambda) tau pi/(2 T_B) = {:.4f} \"/(div s)\n",
                       c.computed_rad_per_div_s / units::kArcsecond);
  out += fmt::format("B1 = {:.3f} div, dt1 = {:+.3f} s; B2 = {:.3f} div, dt2 = {:+.3f} s\n", c.amplitude1_div.value,
                     c.dt1_s.value, c.amplitude2_div.value, c.dt2_s.value);
  out += "gyro north N = " + format_direction_dms(Angle::radians(c.north_rad)) + "\n";
  for (const auto& n : c.notes) out += "note: " + n + "\n";
  return out;
}

namespace {

// "[white]", "[markov1-ml]", "[white*]" (the requested model could not be used).
std::string stochastic_tag(const gyro::StochasticUse& u) {
  return "[" + u.used + (u.fallback ? "*" : "") + "]";
}

}  // namespace

namespace {

// Name, instrument, record sheet, the points and λ at the station.
std::string campaign_header_text(const gyro::CampaignResult& r, const AngleFormat& f) {
  std::string out;
  out += fmt::format("Gyro orientation campaign: {}\n", r.name.empty() ? "(unnamed)" : r.name);
  out += std::string(72, '=') + "\n";
  const auto& rec = r.record;
  const std::pair<const char*, const std::string*> record[] = {
      {"Date", &rec.date},         {"Observer", &rec.observer}, {"Booker", &rec.booker},
      {"Computed by", &rec.computed_by}, {"Checked by", &rec.checked_by}, {"Weather", &rec.weather},
      {"Temperature", &rec.temperature}, {"Remarks", &rec.remarks}};
  if (!r.instrument_name.empty() || !r.instrument_serial.empty())
    out += fmt::format("{:<14} {}{}\n", "Instrument", r.instrument_name,
                       r.instrument_serial.empty() ? "" : " (No. " + r.instrument_serial + ")");
  for (const auto& [key, value] : record)
    if (!value->empty()) out += fmt::format("{:<14} {}\n", key, *value);
  auto point = [&](const char* what, const gyro::PointResult& p) {
    out += fmt::format("{:<14} {:<10} lat {}  lon {}  x {:.3f} m  y {:.3f} m  gamma {}\n", what, p.name,
                       format_dms(Angle::radians(p.lat_rad), {3, true, false}),
                       format_dms(Angle::radians(p.lon_rad), {3, true, false}), p.grid.x_north_m,
                       p.grid.y_east_m, f.dms(p.grid.convergence_rad, 2));
  };
  point("Station", r.station);
  if (r.target) point("Target", *r.target);
  if (r.known_station) point("Known station", *r.known_station);
  const auto& lam = r.instrument_station.instrument.torsion_ratio;
  out += fmt::format("Torsion ratio at the station: {:.5f} (sigma {:.5f})\n\n", lam.value, lam.sigma);
  return out;
}

// The known line's azimuth and determinations (when calibrated there), and E.
std::string calibration_text(const gyro::CampaignResult& r, const AngleFormat& f) {
  std::string out;
  if (r.instrument_constant) {
    out += "Calibration on the known line\n";
    const std::string line =
        r.known_station && r.known_target ? " " + r.known_station->name + "-" + r.known_target->name : "";
    if (r.known_azimuth_given && r.known_azimuth_given->kind != gyro::KnownAzimuth::Kind::Astronomic)
      out += fmt::format("  known azimuth{} ({}, given) {}  sigma {}\n", line,
                         geodesy::to_string(r.known_azimuth_given->kind), f.dir(r.known_azimuth_given->value_rad.value),
                         f.sig(r.known_azimuth_given->value_rad.sigma));
    out += fmt::format("  known azimuth{} (astronomic) {}  sigma {}\n", line, f.dir(r.known_astronomic_azimuth_rad->value),
                       f.sig(r.known_astronomic_azimuth_rad->sigma));
    auto list = [&](const char* when, const std::vector<gyro::DeterminationResult>& d,
                    const std::vector<gyro::Uncertain>& ag, const std::vector<gyro::Uncertain>& e) {
      for (std::size_t i = 0; i < d.size(); ++i)
        out += fmt::format("  {:<6} {:<20} {:<13} N_G {:>15}  A_G {:>15}  E {:>9}  sigma {}\n", when,
                           gyro::to_string(d[i].primary.method), stochastic_tag(d[i].stochastic),
                           f.dir(d[i].primary.north.north_rad), f.dir(ag[i].value),
                           f.sec(e[i].value), f.sig(e[i].sigma));
    };
    list("before", r.known_before, r.known_gyro_azimuths_before, r.instrument_constant->before);
    list("after", r.known_after, r.known_gyro_azimuths_after, r.instrument_constant->after);
  }
  out += fmt::format("  instrument constant E = {}  sigma {}\n\n", f.sec(r.instrument_constant_used_rad.value),
                     f.sig(r.instrument_constant_used_rad.sigma));
  return out;
}

std::string line_determinations_text(const gyro::CampaignResult& r, const AngleFormat& f) {
  std::string out = "Determinations on the line\n";
  for (std::size_t i = 0; i < r.determinations.size(); ++i) {
    const auto& d = r.determinations[i];
    out += fmt::format("  {:<2} {:<20} {:<13} N_G {:>15}  sigma {:>6}  A_G {:>15}  sigma {}\n", i + 1,
                       d.label.empty() ? gyro::to_string(d.primary.method) : d.label,
                       stochastic_tag(d.stochastic), f.dir(d.primary.north.north_rad),
                       f.sig(d.primary.north.sigma_rad), f.dir(r.gyro_azimuths[i].value),
                       f.sig(r.gyro_azimuths[i].sigma));
  }
  out += fmt::format(
      "  [model]: stochastic model of the reversal readings behind N_G (stochastic_model: {}); "
      "white: independent readings; *: the requested model could not be used, white noise (see "
      "Warnings)\n",
      gyro::to_string(r.stochastic_model));
  return out;
}

// A_G → A → α → T, step by step.
std::string chain_text(const gyro::CampaignResult& r, const AngleFormat& f) {
  std::string out = "\nAzimuth chain (station to target)\n";
  const auto& c = r.chain;
  out += fmt::format("  gyro azimuth        A_G = {:>15}  sigma {}\n", f.dir(c.gyro_azimuth_rad.value),
                     f.sig(c.gyro_azimuth_rad.sigma));
  out += fmt::format("  + instrument const. E   = {:>15}\n", f.sec(r.instrument_constant_used_rad.value));
  out += fmt::format("  astronomic azimuth  A   = {:>15}  sigma {}\n", f.dir(c.astronomic_azimuth_rad.value),
                     f.sig(c.astronomic_azimuth_rad.sigma));
  out += fmt::format("  Laplace -eta tan(phi)   = {:>15}\n",
                     c.laplace_applied ? f.sec(c.laplace_correction_rad) : std::string("not applied"));
  if (c.zenith_term_applied)
    out += fmt::format("  -(xi sin a - eta cos a) cot z = {:>9}  (z = {})\n", f.sec(c.zenith_correction_rad),
                       format_dms(Angle::radians(*c.zenith_distance_rad), {0, true, false}));
  out += fmt::format("  geodetic azimuth    alpha = {:>13}  sigma {}\n", f.dir(c.geodetic_azimuth_rad.value),
                     f.sig(c.geodetic_azimuth_rad.sigma));
  out += fmt::format("  - convergence gamma     = {:>15}\n",
                     f.dms(c.convergence_rad, 2));
  out += fmt::format("  + arc-to-chord delta    = {:>15}\n",
                     c.arc_to_chord_applied ? f.sec(c.arc_to_chord_rad) : std::string("not applied"));
  out += fmt::format("  GRID AZIMUTH        T   = {:>15}  sigma {}\n", f.dir(c.grid_azimuth_rad.value),
                     f.sig(c.grid_azimuth_rad.sigma));
  if (r.line_grid_azimuth_from_coordinates_rad) {
    const double d = wrap_signed_rad(c.grid_azimuth_rad.value - *r.line_grid_azimuth_from_coordinates_rad);
    out += fmt::format("  traverse (coordinates)  = {:>15}  gyro - traverse {}\n",
                       f.dir(*r.line_grid_azimuth_from_coordinates_rad),
                       std::fabs(d) >= units::kDegree ? format_dms(Angle::radians(d), {1, true, true}) : f.sec(d));
  }
  out += "\n";
  return out;
}

// The checks with their limits, the one-run standard deviations, notes and warnings.
std::string checks_text(const gyro::CampaignResult& r, const AngleFormat& f) {
  std::string out = fmt::format("Checks (limits: {}, unless marked)\n", r.limits.source);
  if (r.checks.empty()) out += "  (none applicable)\n";
  for (const auto& k : r.checks)
    out += "  " + check_text(k) + (k.source == r.limits.source ? "" : "  [" + k.source + "]") + "\n";
  if (r.constant_one_run_sigma_rad || r.line_one_run_sigma_rad) {
    out += "  one-run standard deviations m = sqrt([vv]/(n-1)):";
    if (r.constant_one_run_sigma_rad) out += " instrument constant " + f.sig(*r.constant_one_run_sigma_rad);
    if (r.constant_one_run_sigma_rad && r.line_one_run_sigma_rad) out += ",";
    if (r.line_one_run_sigma_rad) out += " gyro azimuth on the line " + f.sig(*r.line_one_run_sigma_rad);
    out += "\n";
  }
  if (!r.notes.empty()) out += "\nNotes\n";
  for (const auto& n : r.notes) out += "  - " + n + "\n";
  if (!r.warnings.empty()) out += "\nWarnings\n";
  for (const auto& w : r.warnings) out += "  ! " + w + "\n";
  return out;
}

}  // namespace

std::string campaign_text(const gyro::CampaignResult& r, const AngleFormat& f) {
  return campaign_header_text(r, f) + calibration_text(r, f) + line_determinations_text(r, f) + chain_text(r, f) +
         checks_text(r, f);
}

}  // namespace meridian::report
