#include "meridian/gyro/campaign.hpp"

#include <cmath>

#include <fmt/format.h>

#include "meridian/core/angle.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gravity/gravity_field.hpp"

namespace meridian::gyro {
namespace {

}  // namespace

// Grid coordinates are authoritative when given (mine surveys work on the
// grid); geographic ones given as well are only checked for consistency.
PointResult resolve_point(const PointInput& p, const geodesy::TransverseMercatorGrid& grid,
                          const std::string& field, std::vector<std::string>& warnings) {
  PointResult r;
  r.name = p.name;
  try {
    if (p.x_north_m && p.y_east_m) {
      const auto g = grid.reverse(*p.x_north_m, *p.y_east_m);
      r.lat_rad = g.lat_rad;
      r.lon_rad = g.lon_rad;
      r.grid = grid.forward(g.lat_rad, g.lon_rad);
      r.grid.x_north_m = *p.x_north_m;
      r.grid.y_east_m = *p.y_east_m;
      if (p.lat_rad && p.lon_rad) {
        const double dlat = std::fabs(*p.lat_rad - r.lat_rad);
        const double dlon = std::fabs(*p.lon_rad - r.lon_rad) * std::cos(r.lat_rad);
        if (std::max(dlat, dlon) > 1.0 * units::kArcsecond)
          warnings.push_back(fmt::format(
              "{}: the geographic coordinates given differ from those of the grid coordinates by "
              "{:.1f}\"; the grid coordinates are used",
              field, std::max(dlat, dlon) / units::kArcsecond));
      }
    } else if (p.lat_rad && p.lon_rad) {
      r.lat_rad = *p.lat_rad;
      r.lon_rad = *p.lon_rad;
      r.grid = grid.forward(r.lat_rad, r.lon_rad);
    } else {
      throw InputError("a point needs latitude_deg and longitude_deg, or grid x_m and y_m");
    }
  } catch (Error& e) {
    e.add_context("", std::nullopt, field);
    throw;
  }
  return r;
}

namespace {

struct Counter {
  Progress* progress;
  std::size_t done, total;
};

std::vector<DeterminationResult> reduce_all(const std::vector<DeterminationInput>& dets,
                                            const Instrument& inst, const ReduceOptions& opt,
                                            const std::string& field,
                                            std::vector<Uncertain>& gyro_azimuths,
                                            std::vector<std::string>& warnings, Counter& count) {
  std::vector<DeterminationResult> out;
  for (std::size_t i = 0; i < dets.size(); ++i) {
    report_progress(count.progress, count.done++, count.total, "determinations");
    const std::string f = fmt::format("{}[{}]", field, i);
    try {
      out.push_back(reduce_determination(dets[i], inst, opt));
      gyro_azimuths.push_back(gyro_azimuth(out.back(), dets[i]));
    } catch (Error& e) {
      e.add_context("", std::nullopt, f);
      throw;
    }
    for (const auto& w : out.back().warnings) warnings.push_back(f + ": " + w);
  }
  return out;
}

}  // namespace

namespace {

// η at a point: as given, else from the gravity model (with a note), else none.
std::optional<Uncertain> eta_at(const CampaignInput& in, const PointInput& p, const PointResult& r,
                                std::vector<std::string>& notes) {
  if (p.eta_rad) return p.eta_rad;
  if (!in.deflection_model || !in.deflection_model->field) return std::nullopt;
  const DeflectionModel& m = *in.deflection_model;
  const double h = p.height_m.value_or(0.0);
  const gravity::FieldValues v =
      m.field->evaluate(gravity::GeodeticPoint{r.lat_rad, r.lon_rad, h}, gravity::Quantities::Deflection);
  notes.push_back(fmt::format("{}: eta = {:+.3f}\" (sigma {:.1f}\") from the gravity model {} at h = {:.1f} m{}",
                              r.name.empty() ? "point" : r.name, v.eta_astro_rad / units::kArcsecond,
                              m.sigma_eta_rad / units::kArcsecond, m.description, h,
                              p.height_m ? "" : " (height not given)"));
  return Uncertain{v.eta_astro_rad, m.sigma_eta_rad};
}

}  // namespace

bool CampaignResult::all_checks_pass() const {
  for (const auto& c : checks)
    if (!c.pass) return false;
  return true;
}

CampaignResult process_campaign(const CampaignInput& in, Progress* progress) {
  CampaignResult res;
  Counter count{progress, 0, in.line.determinations.size()};
  if (in.known_line) count.total += in.known_line->before.size() + in.known_line->after.size();
  res.name = in.name;
  const geodesy::TransverseMercatorGrid grid(in.grid);
  res.notes.push_back("grid: " + geodesy::describe(in.grid));

  res.station = resolve_point(in.line.from, grid, "line.from", res.warnings);
  if (in.line.to) res.target = resolve_point(*in.line.to, grid, "line.to", res.warnings);
  try {
    res.instrument_station = resolve_instrument(in.instrument, res.station.lat_rad);
  } catch (Error& e) {
    e.add_context("", std::nullopt, "instrument");
    throw;
  }
  for (const auto& n : res.instrument_station.notes) res.notes.push_back("station C: " + n);

  const double det_tol = in.tolerances.determination_difference_rad.value_or(
      default_determination_tolerance_rad(in.instrument.accuracy_class_arcsec));
  const double e_tol = in.tolerances.instrument_constant_difference_rad.value_or(det_tol);
  ReduceOptions opt = in.options;
  opt.zero_position_tolerance_div = in.tolerances.zero_position_div;

  // 1. Instrument constant.
  if (in.known_line) {
    const KnownLineInput& k = *in.known_line;
    res.known_station = resolve_point(k.from, grid, "known_line.from", res.warnings);
    std::optional<PointResult> known_target;
    if (k.to) known_target = resolve_point(*k.to, grid, "known_line.to", res.warnings);
    try {
      res.instrument_known = resolve_instrument(in.instrument, res.known_station->lat_rad);
    } catch (Error& e) {
      e.add_context("", std::nullopt, "instrument");
      throw;
    }
    for (const auto& n : res.instrument_known->notes) res.notes.push_back("known station: " + n);
    const Instrument& ik = res.instrument_known->instrument;
    res.known_before = reduce_all(k.before, ik, opt, "known_line.before",
                                  res.known_gyro_azimuths_before, res.warnings, count);
    res.known_after = reduce_all(k.after, ik, opt, "known_line.after",
                                 res.known_gyro_azimuths_after, res.warnings, count);

    // Known azimuth → astronomic.
    Uncertain a = k.azimuth.value_rad;
    const double phi = res.known_station->lat_rad;
    if (k.azimuth.kind == KnownAzimuth::Kind::Grid) {
      double alpha = a.value + res.known_station->grid.convergence_rad;
      if (known_target) {
        const double delta = geodesy::arc_to_chord(
            grid, res.known_station->grid.x_north_m, res.known_station->grid.y_east_m,
            known_target->grid.x_north_m, known_target->grid.y_east_m);
        alpha -= delta;
        res.notes.push_back(fmt::format("known line: geodetic azimuth = grid + gamma - delta "
                                        "(gamma {:.2f}\", delta {:.2f}\")",
                                        res.known_station->grid.convergence_rad / units::kArcsecond,
                                        delta / units::kArcsecond));
      } else {
        res.notes.push_back("known line: geodetic azimuth = grid + gamma (no target coordinates, "
                            "arc-to-chord correction neglected)");
      }
      a.value = alpha;
    }
    if (k.azimuth.kind != KnownAzimuth::Kind::Astronomic) {
      if (const auto eta = eta_at(in, k.from, *res.known_station, res.notes)) {
        // Laplace inverted: A = α + η·tan φ.
        a.value += eta->value * std::tan(phi);
        a.sigma = std::hypot(a.sigma, eta->sigma * std::tan(phi));
      } else {
        res.notes.push_back("known line: eta unknown at the known station; the deflection is "
                            "absorbed into E (E relates gyro to geodetic azimuths)");
      }
    }
    a.value = wrap_positive_rad(a.value);
    res.known_astronomic_azimuth_rad = a;
    res.instrument_constant = instrument_constant(a, res.known_gyro_azimuths_before,
                                                  res.known_gyro_azimuths_after, e_tol);
    res.instrument_constant_used_rad = res.instrument_constant->mean;
    for (const auto& w : res.instrument_constant->warnings) res.warnings.push_back(w);
    if (res.instrument_constant->difference_rad)
      res.checks.push_back({"instrument constant, after - before",
                            *res.instrument_constant->difference_rad / units::kArcsecond,
                            e_tol / units::kArcsecond, "arcsec",
                            res.instrument_constant->within_tolerance});
  } else if (in.instrument_constant_rad) {
    res.instrument_constant_used_rad = *in.instrument_constant_rad;
    res.notes.push_back("instrument constant E given, not calibrated in this campaign");
  } else {
    throw InputError("no instrument constant: give known_line (calibration) or instrument_constant",
                     {"", std::nullopt, "known_line"});
  }

  // 2. The unknown line.
  if (in.line.determinations.empty())
    throw InputError("no determination on the line", {"", std::nullopt, "line.determinations"});
  const Instrument& ic = res.instrument_station.instrument;
  res.determinations = reduce_all(in.line.determinations, ic, opt, "line.determinations",
                                  res.gyro_azimuths, res.warnings, count);
  report_progress(progress, count.done, count.total, "determinations");
  res.gyro_azimuth_mean = mean_direction(res.gyro_azimuths);
  if (res.gyro_azimuths.size() >= 2) {
    const bool ok = res.gyro_azimuth_mean.max_difference <= det_tol;
    res.checks.push_back({"line determinations, largest difference",
                          res.gyro_azimuth_mean.max_difference / units::kArcsecond,
                          det_tol / units::kArcsecond, "arcsec", ok});
    if (!ok)
      res.warnings.push_back(fmt::format(
          "gyro azimuths of the line differ by {:.1f}\" (tolerance {:.1f}\")",
          res.gyro_azimuth_mean.max_difference / units::kArcsecond, det_tol / units::kArcsecond));
  } else {
    res.warnings.push_back("only one determination on the line: no independent check");
  }
  // Zero-position stability checks of every determination.
  auto zero_checks = [&](const std::vector<DeterminationResult>& v, const std::string& what) {
    for (std::size_t i = 0; i < v.size(); ++i)
      if (v[i].zero_position && v[i].zero_position->difference_div)
        res.checks.push_back({fmt::format("zero position after - before, {}[{}]", what, i),
                              *v[i].zero_position->difference_div,
                              v[i].zero_position->tolerance_div, "div",
                              v[i].zero_position->within_tolerance});
  };
  zero_checks(res.known_before, "known_line.before");
  zero_checks(res.known_after, "known_line.after");
  zero_checks(res.determinations, "line.determinations");

  // 3. Azimuth chain.
  AzimuthChainInput chain;
  chain.gyro_azimuth_rad = res.gyro_azimuth_mean.mean;
  chain.instrument_constant_rad = res.instrument_constant_used_rad;
  chain.latitude_rad = res.station.lat_rad;
  chain.eta_rad = eta_at(in, in.line.from, res.station, res.notes);
  chain.convergence_rad = res.station.grid.convergence_rad;
  if (res.target)
    chain.arc_to_chord_rad = geodesy::arc_to_chord(grid, res.station.grid.x_north_m,
                                                   res.station.grid.y_east_m,
                                                   res.target->grid.x_north_m,
                                                   res.target->grid.y_east_m);
  res.chain = azimuth_chain(chain);
  for (const auto& n : res.chain.notes) res.notes.push_back(n);
  return res;
}

}  // namespace meridian::gyro
