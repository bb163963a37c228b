#include "meridian/gyro/campaign.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "meridian/core/angle.hpp"
#include "meridian/core/dms.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/geodesy/laplace.hpp"
#include "meridian/geodesy/sight.hpp"
#include "meridian/gyro/stochastic_determination.hpp"

namespace meridian::gyro {

std::string to_string(CheckUnit u) {
  switch (u) {
    case CheckUnit::Div: return "div";
    case CheckUnit::Runs: return "runs";
    case CheckUnit::Observers: return "observers";
    case CheckUnit::Checks: return "checks";
    case CheckUnit::Entries: return "entries";
    case CheckUnit::Seconds: return "s";
    case CheckUnit::Arcsec: break;
  }
  return "arcsec";
}

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
  // A standard zone's point far beyond its half width is another zone's coordinates or the
  // wrong zone number (helper trial, issue 36: 8 deg off was only seen in gyro - traverse).
  // Zones overlap in practice; 0.5 deg beyond the edge is tolerated.
  const auto& def = grid.definition();
  if (def.system != geodesy::ZoneSystem::Custom) {
    const double half_deg = def.system == geodesy::ZoneSystem::GaussKruger3 ? 1.5 : 3.0;
    const double off_deg =
        std::fabs(std::remainder(r.lon_rad - def.central_meridian_rad, 2.0 * units::kPi)) / units::kDegree;
    if (off_deg > half_deg + 0.5)
      warnings.push_back(fmt::format(
          "{}: {:.2f} deg of longitude from the central meridian {:.1f} deg of zone {}, beyond the zone's "
          "half width {:g} deg: the wrong zone, or coordinates of another zone? (convergence "
          "{:.0f}\")",
          field, off_deg, def.central_meridian_rad / units::kDegree, def.zone, half_deg,
          r.grid.convergence_rad / units::kArcsecond));
  }
  return r;
}

namespace {
// A point as the user named it, else its role.
std::string point_label(const PointResult& p, const char* role) { return p.name.empty() ? role : p.name; }
}  // namespace

bool CampaignResult::all_checks_pass() const {
  for (const auto& c : checks)
    if (!c.pass) return false;
  return true;
}

namespace {

// The steps of process(), in order. Each reads the input and fills its part
// of the result.
class CampaignRun {
 public:
  CampaignRun(const CampaignInput& in, Progress* progress, const DeflectionModel* deflection)
      : in_(in), progress_(progress), deflection_(deflection), grid_(in.grid) {
    total_ = in.line.determinations.size();
    if (in.known_line) total_ += in.known_line->before.size() + in.known_line->after.size();
    if (in.gravity_model && !deflection)
      throw InputError("the campaign names a gravity model but it was not loaded",
                       {"", std::nullopt, "gravity_model"});
    try {
      limits_ = apply_tolerances(regulation_limits(accuracy_class()), in.tolerances);
    } catch (Error& e) {
      e.add_context("", std::nullopt, "instrument.accuracy_class_arcsec");
      throw;
    }
    options_ = in.options;
    options_.zero_position_tolerance_div = limits_.zero_position_drift_div;
  }

  CampaignResult run() {
    res_.input = in_;
    res_.name = in_.name;
    res_.limits = limits_;
    res_.record = in_.record;
    res_.stochastic_model = in_.stochastic_model;
    res_.instrument_name = in_.instrument.name;
    res_.instrument_serial = in_.instrument.serial;
    warn_looser_limits();
    res_.notes.push_back("grid: " + geodesy::describe(in_.grid));
    if (in_.stochastic_model != StochasticChoice::White)
      res_.notes.push_back(fmt::format(
          "stochastic_model {}: N_G of every tracking determination by generalised least squares "
          "under that model of its reversal readings, where it can be used (else white noise, "
          "with a warning)",
          to_string(in_.stochastic_model)));
    resolve_station();
    if (in_.known_line) calibrate_on_known_line();
    else use_given_instrument_constant();
    reduce_line();
    check_accuracy_class();
    check_programme();
    check_zero_positions();
    check_line_runs();
    check_target_rounds();
    check_tracking_runs();
    check_booked_periods();
    check_instrument_constants();
    check_duplicated_runs();
    check_observers();
    reduce_azimuth_chain();
    check_line_coordinates();
    return std::move(res_);
  }

 private:
  ResolvedInstrument instrument_at(const PointResult& p) const {
    try {
      return resolve_instrument(in_.instrument, p.lat_rad);
    } catch (Error& e) {
      e.add_context("", std::nullopt, "instrument");
      throw;
    }
  }

  // Station C, target D and the instrument constants at C.
  void resolve_station() {
    res_.station = resolve_point(in_.line.from, grid_, "line.from", res_.warnings);
    if (in_.line.to) res_.target = resolve_point(*in_.line.to, grid_, "line.to", res_.warnings);
    res_.instrument_station = instrument_at(res_.station);
    for (const auto& n : res_.instrument_station.notes) res_.notes.push_back(point_label(res_.station, "station") + ": " + n);
  }

  // Reduce every determination of `dets`, with their gyro azimuths A_G.
  std::vector<DeterminationResult> reduce_all(const std::vector<DeterminationInput>& dets, const Instrument& inst,
                                              const std::string& field, std::vector<Uncertain>& gyro_azimuths) {
    std::vector<DeterminationResult> out;
    for (std::size_t i = 0; i < dets.size(); ++i) {
      report_progress(progress_, done_++, total_, "determinations");
      const std::string f = fmt::format("{}[{}]", field, i);
      try {
        out.push_back(reduce_determination(dets[i], inst, options_));
        // The stochastic model of the reversal readings: the determination's own request (an
        // error when it cannot be used), else the campaign's (white noise when it cannot).
        const StochasticChoice choice = dets[i].stochastic_model.value_or(in_.stochastic_model);
        out.back() = with_stochastic_model(std::move(out.back()), dets[i], inst, choice,
                                           dets[i].stochastic_model.has_value());
        gyro_azimuths.push_back(gyro_azimuth(out.back(), dets[i]));
      } catch (Error& e) {
        e.add_context("", std::nullopt, f);
        throw;
      }
      for (const auto& w : out.back().warnings) res_.warnings.push_back(f + ": " + w);
    }
    return out;
  }

  // ξ and η at a point; either may be unknown.
  struct PointDeflection {
    std::optional<Uncertain> xi_rad, eta_rad;
  };

  // ξ and η at a point: each as given, else from the deflection model (with a
  // note), else none.
  PointDeflection deflection_at(const PointInput& p, const PointResult& r) {
    PointDeflection d{p.xi_rad, p.eta_rad};
    if (!deflection_ || (d.xi_rad && d.eta_rad)) return d;
    const double h = p.height_m.value_or(0.0);
    const geodesy::Deflection m = deflection_->deflection(r.lat_rad, r.lon_rad, h);
    std::string what;
    if (!d.xi_rad) {
      d.xi_rad = Uncertain{m.xi_rad, deflection_->sigma_xi_rad};
      what = fmt::format("xi = {:+.3f}\" (sigma {:.1f}\")", m.xi_rad / units::kArcsecond,
                         deflection_->sigma_xi_rad / units::kArcsecond);
    }
    if (!d.eta_rad) {
      d.eta_rad = Uncertain{m.eta_rad, deflection_->sigma_eta_rad};
      what += fmt::format("{}eta = {:+.3f}\" (sigma {:.1f}\")", what.empty() ? "" : ", ",
                          m.eta_rad / units::kArcsecond, deflection_->sigma_eta_rad / units::kArcsecond);
    }
    res_.notes.push_back(fmt::format("{}: {} from the gravity model {} at h = {:.1f} m{}",
                                     r.name.empty() ? "point" : r.name, what, deflection_->description, h,
                                     p.height_m ? "" : " (height not given)"));
    return d;
  }

  // The deflection at a point as error sources of T (error_sources.hpp): `sign` +1 at the known
  // station (T follows A_known), −1 at the line's station (α = A − η·tan φ + c_z); `zenith_rad` the
  // z of the zenith-distance term where it is applied; `alpha_rad` the geodetic azimuth of the sight.
  void record_deflection_sources(const PointInput& p, const PointResult& r, const PointDeflection& d, double sign,
                                 std::optional<double> zenith_rad, double alpha_rad) {
    const double cot_z = zenith_rad ? 1.0 / std::tan(*zenith_rad) : 0.0;
    const auto source = [&](bool given) { return given ? std::string("given in the file") : deflection_->description; };
    if (d.eta_rad) {
      const double partial = sign * (std::tan(r.lat_rad) - std::cos(alpha_rad) * cot_z);
      res_.shared_error_sources.push_back({ErrorSource::Kind::Eta, source(p.eta_rad.has_value()), r.lat_rad, r.lon_rad,
                                           std::nullopt, std::nullopt, d.eta_rad->value, partial * d.eta_rad->sigma, r.name});
    }
    if (d.xi_rad && zenith_rad) {
      const double partial = sign * std::sin(alpha_rad) * cot_z;
      res_.shared_error_sources.push_back({ErrorSource::Kind::Xi, source(p.xi_rad.has_value()), r.lat_rad, r.lon_rad,
                                           std::nullopt, std::nullopt, d.xi_rad->value, partial * d.xi_rad->sigma, r.name});
    }
  }

  // The sight of a line for the zenith-distance term of the Laplace equation.
  struct Sight {
    std::string label;                  // e.g. "line D1->D2"
    std::optional<double> zenith_rad;   // z, when known
    std::string source;                 // where z came from, for the notes
  };

  // z of the sight from → to: the booked zenith angle, else from the heights
  // of both points (rigorous, geodesy/sight.hpp), else unknown. `required`:
  // the term will be applied, so a z that cannot be used is an error at
  // `field`; otherwise z only informs a note and such a z is dropped.
  Sight sight_of(const std::string& what, const std::string& field, const std::optional<double>& booked,
                 const PointInput& from_in, const PointResult& from, const std::optional<PointInput>& to_in,
                 const std::optional<PointResult>& to, bool required) {
    Sight s;
    const std::string a = from.name.empty() ? "station" : from.name;
    const std::string b = to && !to->name.empty() ? to->name : "target";
    s.label = fmt::format("{} {}->{}", what, a, b);
    if (booked) {
      s.zenith_rad = *booked;
      s.source = "booked (zenith_angle)";
      return s;
    }
    if (!to || !to_in || !from_in.height_m || !to_in->height_m) return s;
    try {
      const double z = geodesy::sight_zenith_distance_rad({from.lat_rad, from.lon_rad, *from_in.height_m},
                                                          {to->lat_rad, to->lon_rad, *to_in->height_m},
                                                          in_.grid.ellipsoid);
      geodesy::check_zenith_distance(z);
      s.zenith_rad = z;
      s.source = fmt::format("from the heights of {} and {}", a, b);
    } catch (Error& e) {
      if (!required) return s;
      e.add_context("", std::nullopt, field + ".to.height_m");
      throw;
    }
    return s;
  }

  // Notes on the zenith-distance term of a line: its value and where z came
  // from; a horizontal sight assumed; or, for an inclined sight, that the
  // term is missing because ξ or η is unknown. Nothing when ξ is unknown and
  // the sight is (nearly) horizontal.
  void note_zenith_term(const Sight& s, const PointDeflection& d, const std::string& station, bool applied,
                        double correction_rad) {
    // |cot z| from which a missing term is worth a note: 0.1″ per 10″ of deflection.
    constexpr double kNoteCotZenith = 0.01;
    const auto zdms = [](double z) { return format_dms(Angle::radians(z), {0, true, false}); };
    if (applied) {
      res_.notes.push_back(fmt::format(
          "{}: zenith distance {} {}; zenith-distance term of the Laplace equation "
          "-(xi sin(alpha) - eta cos(alpha)) cot(z) = {:+.3f}\"",
          s.label, zdms(*s.zenith_rad), s.source, correction_rad / units::kArcsecond));
    } else if (d.xi_rad && d.eta_rad && !s.zenith_rad) {
      res_.notes.push_back(fmt::format(
          "{}: no zenith_angle and no heights of both points: the sight is taken as horizontal "
          "(zenith-distance term of the Laplace equation omitted)",
          s.label));
    } else if (s.zenith_rad && std::abs(1.0 / std::tan(*s.zenith_rad)) >= kNoteCotZenith) {
      const double cot_z = 1.0 / std::tan(*s.zenith_rad);
      const char* unknown = !d.xi_rad && !d.eta_rad ? "xi and eta" : (!d.xi_rad ? "xi" : "eta");
      res_.notes.push_back(fmt::format(
          "{}: the sight is inclined {:+.1f} deg (zenith distance {} {}); the zenith-distance term "
          "of the Laplace equation, up to {:.2f}\" per 10\" of deflection here, is not applied: {} "
          "unknown at {}",
          s.label, 90.0 - *s.zenith_rad / units::kDegree, zdms(*s.zenith_rad), s.source,
          10.0 * std::abs(cot_z), unknown, station));
    }
  }

  // The known line's azimuth as an astronomic azimuth (the inverse chain).
  Uncertain known_astronomic_azimuth(const KnownLineInput& k, const std::optional<PointResult>& known_target) {
    const PointResult& from = *res_.known_station;
    geodesy::AzimuthReduction red;
    red.latitude_rad = from.lat_rad;
    red.convergence_rad = from.grid.convergence_rad;
    if (k.azimuth.kind == geodesy::AzimuthKind::Grid) {
      if (known_target) {
        red.arc_to_chord_rad = geodesy::arc_to_chord(grid_, from.grid.x_north_m, from.grid.y_east_m,
                                                     known_target->grid.x_north_m, known_target->grid.y_east_m);
        res_.notes.push_back(fmt::format("known line: geodetic azimuth = grid + gamma - delta "
                                         "(gamma {:.2f}\", delta {:.2f}\")",
                                         from.grid.convergence_rad / units::kArcsecond,
                                         *red.arc_to_chord_rad / units::kArcsecond));
      } else {
        res_.notes.push_back("known line: geodetic azimuth = grid + gamma (no target coordinates, "
                             "arc-to-chord correction neglected)");
      }
    }
    ErrorSource given{ErrorSource::Kind::KnownAzimuth, fmt::format("known_line.azimuth ({})", to_string(k.azimuth.kind)),
                      from.lat_rad, from.lon_rad, std::nullopt, std::nullopt, k.azimuth.value_rad.value,
                      k.azimuth.value_rad.sigma, from.name};
    if (known_target) given.to_lat_rad = known_target->lat_rad, given.to_lon_rad = known_target->lon_rad;
    res_.shared_error_sources.push_back(given);
    if (k.azimuth.kind == geodesy::AzimuthKind::Astronomic)
      return geodesy::azimuth_steps(k.azimuth.kind, k.azimuth.value_rad, red).astronomic_rad;
    const PointDeflection d = deflection_at(k.from, from);
    red.eta_rad = d.eta_rad;
    if (!red.eta_rad) {
      e_holds_deflection_ = true;
      res_.notes.push_back("known line: eta unknown at the known station; the deflection is "
                           "absorbed into E (E relates gyro to geodetic azimuths)");
    }
    const bool full = d.xi_rad && d.eta_rad;
    const Sight sight =
        sight_of("known line", "known_line", k.zenith_angle_rad, k.from, from, k.to, known_target, full);
    if (full) {
      red.xi_rad = d.xi_rad;
      red.zenith_distance_rad = sight.zenith_rad;
    }
    const geodesy::AzimuthSteps steps = geodesy::azimuth_steps(k.azimuth.kind, k.azimuth.value_rad, red);
    record_deflection_sources(k.from, from, d, +1.0,
                              steps.zenith_term_applied ? sight.zenith_rad : std::nullopt, steps.geodetic_rad.value);
    note_zenith_term(sight, d, from.name.empty() ? "the known station" : from.name, steps.zenith_term_applied,
                     steps.zenith_correction_rad);
    return steps.astronomic_rad;
  }

  // Step 1: the instrument constant E from determinations on the known line.
  void calibrate_on_known_line() {
    const KnownLineInput& k = *in_.known_line;
    res_.known_station = resolve_point(k.from, grid_, "known_line.from", res_.warnings);
    if (k.to) res_.known_target = resolve_point(*k.to, grid_, "known_line.to", res_.warnings);
    const std::optional<PointResult>& known_target = res_.known_target;
    res_.known_azimuth_given = k.azimuth;
    res_.instrument_known = instrument_at(*res_.known_station);
    for (const auto& n : res_.instrument_known->notes)
      res_.notes.push_back(point_label(*res_.known_station, "known station") + ": " + n);
    const Instrument& ik = res_.instrument_known->instrument;
    res_.known_before = reduce_all(k.before, ik, "known_line.before", res_.known_gyro_azimuths_before);
    res_.known_after = reduce_all(k.after, ik, "known_line.after", res_.known_gyro_azimuths_after);

    const Uncertain a = known_astronomic_azimuth(k, known_target);
    res_.known_astronomic_azimuth_rad = a;
    res_.instrument_constant = instrument_constant(a, res_.known_gyro_azimuths_before, res_.known_gyro_azimuths_after,
                                                   limits_.constant_means_rad);
    res_.instrument_constant_used_rad = res_.instrument_constant->mean;
    for (const auto& w : res_.instrument_constant->warnings) res_.warnings.push_back(w);
    if (known_target)
      res_.known_grid_azimuth_from_coordinates_rad =
          geodesy::grid_azimuth(res_.known_station->grid.x_north_m, res_.known_station->grid.y_east_m,
                                known_target->grid.x_north_m, known_target->grid.y_east_m);
  }

  void use_given_instrument_constant() {
    if (!in_.instrument_constant_rad)
      throw InputError("no instrument constant: give known_line (calibration) or instrument_constant",
                       {"", std::nullopt, "known_line"});
    res_.instrument_constant_used_rad = *in_.instrument_constant_rad;
    res_.shared_error_sources.push_back({ErrorSource::Kind::InstrumentConstant, "instrument_constant", 0.0, 0.0,
                                         std::nullopt, std::nullopt, in_.instrument_constant_rad->value,
                                         in_.instrument_constant_rad->sigma, ""});
    res_.notes.push_back("instrument constant E given, not calibrated in this campaign");
  }

  // Step 2: the determinations on the unknown line.
  void reduce_line() {
    if (in_.line.determinations.empty())
      throw InputError("no determination on the line", {"", std::nullopt, "line.determinations"});
    res_.determinations = reduce_all(in_.line.determinations, res_.instrument_station.instrument,
                                     "line.determinations", res_.gyro_azimuths);
    report_progress(progress_, done_, total_, "determinations");
    res_.gyro_azimuth_mean = mean_direction(res_.gyro_azimuths);
  }

  // The checks of the regulations (regulations.hpp), in the order of its table.
  void add_check(std::string name, double value, double limit, CheckUnit unit, const std::optional<double>& override_,
                 const char* override_key, bool minimum = false, bool signed_value = false, std::string field = {}) {
    const bool pass = minimum ? value >= limit : std::fabs(value) <= limit;
    res_.checks.push_back({std::move(name), value, limit, unit, pass, minimum, signed_value,
                           override_ ? fmt::format("tolerances.{} in the file", override_key) : limits_.source,
                           std::move(field)});
  }
  void add_angle_check(std::string name, double value_rad, double limit_rad, const std::optional<double>& override_,
                       const char* override_key, bool signed_value = false, std::string field = {}) {
    add_check(std::move(name), value_rad / units::kArcsecond, limit_rad / units::kArcsecond, CheckUnit::Arcsec,
              override_, override_key, false, signed_value, std::move(field));
  }

  // A limit set in the file that is looser than the regulations' for the
  // class is allowed (a project may decide so) but said aloud.
  void warn_looser_limits() {
    const RegulationLimits reg = regulation_limits(accuracy_class());
    const Tolerances& t = in_.tolerances;
    const struct {
      const std::optional<double>& set;
      double regulation;
      const char* key;
      double unit;
      const char* unit_name;
    } rows[] = {
        {t.determination_difference_rad, reg.run_difference_rad, "determination_difference_arcsec", units::kArcsecond, "\""},
        {t.instrument_constant_difference_rad, reg.constant_difference_rad, "instrument_constant_difference_arcsec",
         units::kArcsecond, "\""},
        {t.instrument_constant_means_rad, reg.constant_means_rad, "instrument_constant_means_arcsec", units::kArcsecond,
         "\""},
        {t.orientation_difference_rad, reg.orientation_difference_rad, "orientation_difference_arcsec",
         units::kArcsecond, "\""},
        {t.orientation_mean_sigma_rad, reg.orientation_mean_sigma_rad, "orientation_mean_sigma_arcsec",
         units::kArcsecond, "\""},
        {t.zero_position_div, reg.zero_position_drift_div, "zero_position_div", 1.0, " div"},
        {t.zero_position_limit_div, reg.zero_position_div, "zero_position_limit_div", 1.0, " div"},
    };
    for (const auto& r : rows)
      if (r.set && *r.set > r.regulation * (1.0 + 1e-12))
        res_.warnings.push_back(fmt::format("tolerances.{} = {:g}{} in the file is looser than the {:g}{} of {}", r.key,
                                            *r.set / r.unit, r.unit_name, r.regulation / r.unit, r.unit_name,
                                            reg.source));
  }

  // The class the limits are taken for: as booked; not booked, the class the instrument's name
  // states, else the 15" default.
  double accuracy_class() const {
    if (in_.instrument.accuracy_class_booked) return in_.instrument.accuracy_class_arcsec;
    return accuracy_class_from_name(in_.instrument.name).value_or(in_.instrument.accuracy_class_arcsec);
  }

  // The class sets every limit: it must be booked, and no looser than the instrument's name
  // states (a 25" class booked for a JT15 gives 70" limits instead of 40").
  void check_accuracy_class() {
    const std::optional<double> named = accuracy_class_from_name(in_.instrument.name);
    const double used = limits_.accuracy_class_arcsec;
    if (!in_.instrument.accuracy_class_booked) {
      const std::string why = named ? fmt::format("the class of its name, {}", in_.instrument.name)
                                    : std::string("Meridian's default");
      res_.checks.push_back({fmt::format("accuracy class booked (not booked: the {:g}\" limits of {} used)", used, why),
                             0.0, 1.0, CheckUnit::Entries, false, true, false,
                             "the class sets every limit of the regulations: book instrument.accuracy_class_arcsec",
                             "instrument"});
      res_.warnings.push_back(fmt::format(
          "instrument.accuracy_class_arcsec not booked: the limits of a {:g}\" instrument ({}) are used", used, why));
      return;
    }
    if (!named) return;
    res_.checks.push_back({fmt::format("accuracy class booked against the instrument's name ({} is a {:g}\" instrument)",
                                       in_.instrument.name, *named),
                           used, *named, CheckUnit::Arcsec, used <= *named, false, false,
                           "the class of the name (gyro/instrument_spec.hpp, accuracy_class_from_name); a tighter "
                           "class booked is accepted",
                           "instrument.accuracy_class_arcsec"});
    if (!res_.checks.back().pass)
      res_.warnings.push_back(fmt::format(
          "instrument.accuracy_class_arcsec = {:g}\" is looser than the {:g}\" of a {}: the checks use looser limits",
          used, *named, in_.instrument.name));
  }

  // The programme of one orientation: runs before, on the line and after.
  void check_programme() {
    if (!in_.known_line) return;
    const auto runs = [](std::size_t n) { return static_cast<double>(n); };
    const std::optional<double> none;
    add_check("programme: runs on the known line before", runs(in_.known_line->before.size()),
              limits_.min_runs_before, CheckUnit::Runs, none, "", true, false, "known_line.before");
    add_check("programme: runs on the line", runs(in_.line.determinations.size()), limits_.min_runs_line,
              CheckUnit::Runs, none, "", true, false, "line.determinations");
    add_check("programme: runs on the known line after", runs(in_.known_line->after.size()), limits_.min_runs_after,
              CheckUnit::Runs, none, "", true, false, "known_line.after");
  }

  // Every run: its zero position observed, within its limit, and stable.
  void check_zero_positions() {
    const Tolerances& t = in_.tolerances;
    // A zero-position run missing (observed < required sides): the limit is the regulations', whatever the class.
    auto sides_observed = [&](std::string name, int observed, int required, std::string field) {
      res_.checks.push_back({std::move(name), static_cast<double>(observed), static_cast<double>(required),
                             CheckUnit::Runs, observed >= required, true, false,
                             "coal-mine surveying regulations: zero position before and after every run",
                             std::move(field)});
    };
    auto checks = [&](const std::vector<DeterminationResult>& v, const std::string& what) {
      for (std::size_t i = 0; i < v.size(); ++i) {
        const std::string run = fmt::format("{}[{}]{}", what, i, v[i].label.empty() ? "" : " (" + v[i].label + ")");
        const std::string field = fmt::format("{}[{}]", what, i);
        if (!v[i].zero_position_used) {
          res_.warnings.push_back(fmt::format(
              "{}: no zero position observed: the correction -lambda tau alpha_p is not applied (it reaches "
              "{:.0f}\" at the limit |alpha_p| = {} div)",
              run,
              res_.instrument_station.instrument.torsion_ratio.value * res_.instrument_station.instrument.scale_value_rad *
                  limits_.zero_position_div / units::kArcsecond,
              limits_.zero_position_div));
          sides_observed("zero position observed, " + run, 0, 1, field);
          continue;
        }
        const auto& z = v[i].zero_position;
        if (z) {
          double largest = 0.0;
          const char* which = "";
          for (const auto& [e, when] : {std::pair{&z->before, "before"}, std::pair{&z->after, "after"}})
            if (*e && std::fabs((*e)->fit.centre.value) >= std::fabs(largest)) {
              largest = (*e)->fit.centre.value;
              which = when;
            }
          add_check(fmt::format("zero position alpha_p (motor-off run {} the gyro run, the larger), {}", which, run),
                    largest, limits_.zero_position_div, CheckUnit::Div, t.zero_position_limit_div,
                    "zero_position_limit_div", false, true, field + ".zero_position." + which);
          if (z->difference_div)
            add_check("zero position after - before, " + run, *z->difference_div, limits_.zero_position_drift_div,
                      CheckUnit::Div, t.zero_position_div, "zero_position_div", false, true,
                      field + ".zero_position");
          else  // one side only: the stability the regulations ask for is not checked (a crew mistake)
            sides_observed(fmt::format("zero position observed before and after, {} (only {})", run,
                                       z->before ? "before" : "after"),
                           1, 2, field + ".zero_position");
        } else {
          add_check("zero position alpha_p (given), " + run, v[i].zero_position_used->value,
                    limits_.zero_position_div, CheckUnit::Div, t.zero_position_limit_div, "zero_position_limit_div",
                    false, true, field + ".zero_position");
          // A value typed in is not the motor-off runs the regulations want on both sides of the run: it is
          // held to the same rule as a run observed on one side only.
          sides_observed(fmt::format("zero position observed before and after, {} (given as a value, not observed)", run),
                         0, 2, field + ".zero_position");
        }
      }
    };
    checks(res_.known_before, "known_line.before");
    checks(res_.known_after, "known_line.after");
    checks(res_.determinations, "line.determinations");
  }

  // A booked period_s against the period the transit times imply: T_A booked for T_B, or another
  // station's period, scales ΔN by the ratio (428.4/466.4 moves T by several arc-seconds).
  void check_booked_periods() {
    auto checks = [&](const std::vector<DeterminationResult>& v, const std::vector<DeterminationInput>& in,
                      const std::string& what) {
      for (std::size_t i = 0; i < v.size() && i < in.size(); ++i) {
        const auto& b = v[i].primary.beta;
        if (!b || !b->period_from_passages_s || !in[i].nontracking.period_s) continue;
        const Uncertain booked = *in[i].nontracking.period_s, implied = *b->period_from_passages_s;
        const double diff = implied.value - booked.value;
        const double limit = std::max(3.0 * std::hypot(implied.sigma, booked.sigma), kPeriodFloor_s);
        res_.checks.push_back(
            {fmt::format("booked period agrees with the transit times, {}[{}]{}: passages {:.1f} s, booked {:.1f} s",
                         what, i, v[i].label.empty() ? "" : " (" + v[i].label + ")", implied.value, booked.value),
             diff, limit, CheckUnit::Seconds, std::abs(diff) <= limit, false, true,
             "Meridian plausibility limit: max(3 sigma of the difference, 1 s)",
             fmt::format("{}[{}].period_s", what, i)});
      }
    };
    if (in_.known_line) {
      checks(res_.known_before, in_.known_line->before, "known_line.before");
      checks(res_.known_after, in_.known_line->after, "known_line.after");
    }
    checks(res_.determinations, in_.line.determinations, "line.determinations");
  }
  static constexpr double kPeriodFloor_s = 1.0;

  // Any two runs on the line, and their one-run standard deviation.
  void check_line_runs() {
    if (res_.gyro_azimuths.size() < 2) {
      res_.warnings.push_back("only one determination on the line: no independent check");
      return;
    }
    res_.line_one_run_sigma_rad = res_.gyro_azimuth_mean.one_run_sigma;
    const double spread = res_.gyro_azimuth_mean.max_difference;
    add_angle_check("any two runs on the line, gyro azimuths", spread, limits_.run_difference_rad,
                    in_.tolerances.determination_difference_rad, "determination_difference_arcsec", false,
                    "line.determinations");
    if (!res_.checks.back().pass)
      res_.warnings.push_back(fmt::format("gyro azimuths of the line differ by {:.1f}\" (limit {:.1f}\")",
                                          spread / units::kArcsecond, limits_.run_difference_rad / units::kArcsecond));
  }

  // The target rounds of every run agree (a face reading booked wrong moves the run's target
  // reading by half of it; a round with its faces swapped is 180° from the others). Meridian's
  // plausibility limits, as determination.cpp's warning: directions within max(10", 3·σ·√2),
  // 2C within 20". The instrument's 2C, the median over every round of the job, tells which
  // round of a failing run is the wrong one.
  static std::vector<std::string> two_c_arcsec(const TargetDirection& t) {
    std::vector<std::string> v;
    for (double c : t.two_c_rad) v.push_back(fmt::format("{:+.1f}\"", c / units::kArcsecond));
    return v;
  }

  void check_target_rounds() {
    struct Run {
      const DeterminationResult* result;
      const DeterminationInput* input;
      std::string field;
    };
    std::vector<Run> runs;
    auto add = [&](const std::vector<DeterminationResult>& v, const std::vector<DeterminationInput>& in,
                   const char* what) {
      for (std::size_t i = 0; i < v.size() && i < in.size(); ++i)
        if (v[i].target && v[i].target->round_rad.size() >= 2)
          runs.push_back({&v[i], &in[i], fmt::format("{}[{}]", what, i)});
    };
    if (in_.known_line) {
      add(res_.known_before, in_.known_line->before, "known_line.before");
      add(res_.known_after, in_.known_line->after, "known_line.after");
    }
    add(res_.determinations, in_.line.determinations, "line.determinations");
    if (runs.empty()) return;
    std::vector<double> all_two_c;
    for (const Run& r : runs)
      for (double c : r.result->target->two_c_rad) all_two_c.push_back(c);
    std::nth_element(all_two_c.begin(), all_two_c.begin() + static_cast<std::ptrdiff_t>(all_two_c.size() / 2),
                     all_two_c.end());
    const double instrument_two_c = all_two_c[all_two_c.size() / 2];
    const auto arcsec = [](double rad) { return rad / units::kArcsecond; };
    for (const Run& r : runs) {
      const TargetDirection& t = *r.result->target;
      const RoundsAgreement agreement = rounds_agreement(t, r.input->target_round_sigma_rad);
      const double limit = agreement.spread_limit_rad;
      const double two_c_variation = agreement.two_c_variation_rad;
      // The same face reading booked wrong in every round of a run keeps its rounds in agreement but
      // moves their 2C together: held to the instrument's (the job's median 2C, from three runs or more).
      std::size_t far = 0;
      for (std::size_t j = 1; j < t.two_c_rad.size(); ++j)
        if (std::fabs(t.two_c_rad[j] - instrument_two_c) > std::fabs(t.two_c_rad[far] - instrument_two_c)) far = j;
      const bool two_c_off = runs.size() >= 3 && agreement.agree && t.spread_rad <= units::kPi / 2 &&
                             std::fabs(t.two_c_rad[far] - instrument_two_c) > kTwoCVariationLimit_rad;
      const bool pass = agreement.agree && !two_c_off;
      const std::string label = r.result->label.empty() ? "" : " (" + r.result->label + ")";
      std::string name = fmt::format("target rounds agree, {}{}", r.field, label);
      std::string field = r.field + ".target_rounds";
      if (two_c_off) {
        field = fmt::format("{}.target_rounds[{}]", r.field, far);
        name += fmt::format(": the rounds agree, but their 2C ({}) differ from the instrument's {:+.1f}\" (the job's median) "
                            "by more than {:.0f}\": the same face reading booked wrong in each round?",
                            fmt::join(two_c_arcsec(t), ", "), arcsec(instrument_two_c), arcsec(kTwoCVariationLimit_rad));
      } else if (!pass) {
        // The round whose 2C is farthest from the instrument's.
        std::size_t k = 0;
        for (std::size_t j = 1; j < t.two_c_rad.size(); ++j)
          if (std::fabs(t.two_c_rad[j] - instrument_two_c) > std::fabs(t.two_c_rad[k] - instrument_two_c)) k = j;
        // Faces swapped: the round is 180° from the others and its 2C is the instrument's negated.
        const bool swapped = t.spread_rad > units::kPi / 2;
        const bool known = std::fabs(t.two_c_rad[k] - instrument_two_c) > 2.0 * units::kArcsecond;
        const std::string which = known ? fmt::format("target_rounds[{}]", k) : std::string("one of the rounds");
        if (known) field = fmt::format("{}.target_rounds[{}]", r.field, k);
        if (swapped)
          name += fmt::format(": {} is 180 deg from the others, face left and face right swapped? (its 2C {:+.1f}\", "
                              "the instrument's {:+.1f}\")",
                              which, arcsec(t.two_c_rad[k]), arcsec(instrument_two_c));
        else
          name += fmt::format(": {}: a face reading booked wrong? (its 2C {:+.1f}\", the instrument's {:+.1f}\"; 2C of "
                              "the rounds varies by {:.1f}\", limit {:.0f}\")",
                              which, arcsec(t.two_c_rad[k]), arcsec(instrument_two_c), arcsec(two_c_variation),
                              arcsec(kTwoCVariationLimit_rad));
      }
      res_.checks.push_back({std::move(name), arcsec(t.spread_rad), arcsec(limit), CheckUnit::Arcsec, pass, false,
                             false,
                             "Meridian plausibility limit: round directions within max(10\", 3 sqrt(2) sigma of a "
                             "round), 2C within 20\" of each other and of the job's median",
                             std::move(field)});
    }
  }

  // Each tracking run's internal check: its readings scatter about the model as their stated σ
  // says (the global test of ReversalResult). A run booked without sigma_reading_arcsec is
  // tested against the class's default (RegulationLimits::default_reading_sigma_rad, with a
  // note), so that a reversal booked 1' wrong fails whatever was booked; its σ stays the
  // a-posteriori one (reversal.hpp), the default only tests.
  void check_tracking_runs() {
    auto checks = [&](const std::vector<DeterminationResult>& v, const std::string& what) {
      for (std::size_t i = 0; i < v.size(); ++i) {
        const auto& rev = v[i].primary.reversal;
        if (!rev) continue;
        std::optional<adjust::GlobalTestResult> test = rev->reading_sigma_test;
        double sigma = rev->sigma_reading;
        std::string stated = "the stated";
        if (!test) {
          if (rev->dof <= 0 || !std::isfinite(rev->sigma0)) continue;
          sigma = limits_.default_reading_sigma_rad;
          const double ratio = rev->sigma0 / sigma;
          test = adjust::global_test(rev->dof * ratio * ratio, rev->dof, kReadingSigmaTestAlpha);
          stated = fmt::format("the {:g}\" class's default (no sigma_reading_arcsec booked: class/3)",
                               limits_.accuracy_class_arcsec);
          res_.notes.push_back(fmt::format(
              "{}[{}]: no sigma_reading_arcsec booked: its readings are checked against {:.1f}\", the {:g}\" "
              "class's default (class/3); its sigma is the a-posteriori one of its readings",
              what, i, sigma / units::kArcsecond, limits_.accuracy_class_arcsec));
        }
        const adjust::GlobalTestResult& g = *test;
        const double limit = sigma * std::sqrt(g.critical_value / g.dof);
        res_.checks.push_back(
            {fmt::format("tracking readings scatter as stated, {}[{}]{}", what, i,
                         v[i].label.empty() ? "" : " (" + v[i].label + ")"),
             rev->sigma0 / units::kArcsecond, limit / units::kArcsecond, CheckUnit::Arcsec, !g.rejected, false, false,
             fmt::format("global test at {:g} %: sigma of a reading from the residuals against {} {:.1f}\"",
                         100.0 * g.alpha, stated, sigma / units::kArcsecond),
             fmt::format("{}[{}].reversals", what, i)});
      }
    };
    checks(res_.known_before, "known_line.before");
    checks(res_.known_after, "known_line.after");
    checks(res_.determinations, "line.determinations");
  }

  // The instrument constants on the known line: any two runs, the before and
  // after means, their plausibility, and the given azimuth of the known line
  // against its coordinates.
  void check_instrument_constants() {
    const Tolerances& t = in_.tolerances;
    if (res_.instrument_constant) {
      const InstrumentConstantResult& e = *res_.instrument_constant;
      std::vector<Uncertain> all = e.before;
      all.insert(all.end(), e.after.begin(), e.after.end());
      if (all.size() >= 2) {
        const AzimuthMean m = mean_direction(all);
        res_.constant_one_run_sigma_rad = m.one_run_sigma;
        // Name the two runs that differ most.
        std::size_t lo = 0, hi = 0;
        for (std::size_t i = 1; i < all.size(); ++i) {
          if (wrap_signed_rad(all[i].value - all[lo].value) < 0) lo = i;
          if (wrap_signed_rad(all[i].value - all[hi].value) > 0) hi = i;
        }
        const auto run = [&](std::size_t i) {
          return i < e.before.size() ? fmt::format("known_line.before[{}]", i)
                                     : fmt::format("known_line.after[{}]", i - e.before.size());
        };
        add_angle_check(fmt::format("any two runs on the known line, instrument constants (largest: {} and {})",
                                    run(lo), run(hi)),
                        m.max_difference, limits_.constant_difference_rad, t.instrument_constant_difference_rad,
                        "instrument_constant_difference_arcsec", false, "known_line");
      }
      if (e.difference_rad)
        add_angle_check("instrument constant, mean after - mean before", *e.difference_rad, limits_.constant_means_rad,
                        t.instrument_constant_means_rad ? t.instrument_constant_means_rad
                                                        : t.instrument_constant_difference_rad,
                        t.instrument_constant_means_rad ? "instrument_constant_means_arcsec"
                                                        : "instrument_constant_difference_arcsec",
                        true, "known_line.after");
      check_known_azimuth();
    }
    const double e = res_.instrument_constant_used_rad.value;
    add_angle_check("instrument constant E plausible", e, limits_.instrument_constant_max_rad,
                    t.instrument_constant_max_rad, "instrument_constant_max_arcsec", true,
                    in_.known_line ? "known_line.azimuth" : "instrument_constant");
    if (!t.instrument_constant_max_rad)
      res_.checks.back().source = "Meridian plausibility limit: |E| of a gyro-theodolite is well under 10'";
    if (!res_.checks.back().pass)
      res_.warnings.push_back(fmt::format(
          "the instrument constant E = {:+.1f}\" is implausibly large: check the known azimuth, its kind "
          "({}) and the target readings of the known line",
          e / units::kArcsecond, in_.known_line ? geodesy::to_string(in_.known_line->azimuth.kind) : "given"));
  }

  // The given azimuth of the known line against the azimuth of its chord
  // from the coordinates in the same file, both as grid azimuths. A given
  // grid azimuth is the coordinates' own (坐标反算): it must agree to their
  // rounding. A given geodetic or astronomic azimuth is an observation of
  // its own: it goes through the chain (an astronomic one keeps its
  // deflection, a few arc-seconds, as no η is applied here) and is held to
  // max(3σ, the class).
  void check_known_azimuth() {
    if (!res_.known_grid_azimuth_from_coordinates_rad) return;
    const KnownLineInput& k = *in_.known_line;
    const PointResult& from = *res_.known_station;
    const PointResult& to = *res_.known_target;
    geodesy::AzimuthReduction red;
    red.latitude_rad = from.lat_rad;
    red.convergence_rad = from.grid.convergence_rad;
    red.arc_to_chord_rad =
        geodesy::arc_to_chord(grid_, from.grid.x_north_m, from.grid.y_east_m, to.grid.x_north_m, to.grid.y_east_m);
    if (k.azimuth.kind == geodesy::AzimuthKind::Astronomic) red.eta_rad = k.from.eta_rad;
    const double given_grid = geodesy::azimuth_steps(k.azimuth.kind, k.azimuth.value_rad, red).grid_rad.value;
    const double diff = wrap_signed_rad(given_grid - *res_.known_grid_azimuth_from_coordinates_rad);
    const auto& override_ = in_.tolerances.known_azimuth_coordinates_rad;
    const bool booked_grid = k.to && k.from.x_north_m && k.from.y_east_m && k.to->x_north_m && k.to->y_east_m;
    double limit = 0.0;
    std::string source, name;
    if (k.azimuth.kind == geodesy::AzimuthKind::Grid && booked_grid) {
      // Half the last booked digit of each coordinate, and half a second for the azimuth's own digit.
      const auto half = [](const std::optional<double>& booked, double value) {
        return booked.value_or(half_unit(value));
      };
      const double ux = half(k.from.x_half_unit_m, *k.from.x_north_m) + half(k.to->x_half_unit_m, *k.to->x_north_m);
      const double uy = half(k.from.y_half_unit_m, *k.from.y_east_m) + half(k.to->y_half_unit_m, *k.to->y_east_m);
      const double rounding =
          geodesy::grid_azimuth_rounding(*k.from.x_north_m, *k.from.y_east_m, *k.to->x_north_m, *k.to->y_east_m, ux, uy);
      limit = rounding + kAzimuthDigitRad;
      name = "known line: the given grid azimuth against its coordinates, to their rounding";
      source = fmt::format(
          "the coordinates' booked digits (x +-{:g} m, y +-{:g} m over both points: {:.2f}\") and half a second "
          "of the booked azimuth",
          ux, uy, rounding / units::kArcsecond);
    } else {
      limit = std::max(3.0 * k.azimuth.value_rad.sigma, limits_.accuracy_class_arcsec * units::kArcsecond);
      name = fmt::format("known line: the given {} azimuth against its coordinates", geodesy::to_string(k.azimuth.kind));
      source = "Meridian plausibility limit: max(3 sigma of the given azimuth, the class)";
    }
    if (override_) {
      limit = *override_;
      source = "tolerances.known_azimuth_coordinates_arcsec in the file";
    }
    if (std::fabs(wrap_signed_rad(diff - units::kPi)) <= units::kDegree)
      name += fmt::format(" (180 deg apart: from and to swapped? the coordinates give {}->{} {})", from.name, to.name,
                          format_direction_dms(Angle::radians(*res_.known_grid_azimuth_from_coordinates_rad)));
    res_.checks.push_back({std::move(name), diff / units::kArcsecond, limit / units::kArcsecond, CheckUnit::Arcsec,
                           std::fabs(diff) <= limit, false, true, std::move(source), "known_line.azimuth.value"});
    if (!res_.checks.back().pass)
      res_.warnings.push_back(fmt::format(
          "the given azimuth of the known line {} differs by {:+.1f}\" from the azimuth {} of the coordinates of "
          "{} and {}: check the azimuth, its kind and the coordinates",
          format_direction_dms(Angle::radians(given_grid)), diff / units::kArcsecond,
          format_direction_dms(Angle::radians(*res_.known_grid_azimuth_from_coordinates_rad)), from.name, to.name));
  }

  // Half the last digit of a coordinate set in code: the decimals of the shortest text that
  // reads back as the same number (3611402.317 -> 0.0005 m). At most 0.5 m, at least 0.05 mm.
  static double half_unit(double booked_m) {
    return std::max(geodesy::half_last_digit_m(fmt::format("{}", booked_m)), 0.5e-4);
  }
  static constexpr double kAzimuthDigitRad = 0.5 * units::kArcsecond;

  // The gyro's grid azimuth of the line against the azimuth of its end points' coordinates
  // (gyro − traverse, what the record sheet reports). Beyond 1° (a line booked from/to the
  // wrong way round, a wrong point) the check fails whatever the file's limit.
  void check_line_coordinates() {
    if (!res_.target) return;
    const double from_coordinates = geodesy::grid_azimuth(res_.station.grid.x_north_m, res_.station.grid.y_east_m,
                                                          res_.target->grid.x_north_m, res_.target->grid.y_east_m);
    res_.line_grid_azimuth_from_coordinates_rad = from_coordinates;
    const double diff = wrap_signed_rad(res_.chain.grid_azimuth_rad.value - from_coordinates);
    const auto& override_ = in_.tolerances.line_coordinates_rad;
    const double limit = override_.value_or(limits_.orientation_difference_rad);
    const bool gross = std::fabs(diff) > units::kDegree;
    const bool reversed = std::fabs(wrap_signed_rad(diff - units::kPi)) <= units::kDegree;
    const std::string a = point_label(res_.station, "station"), b = point_label(*res_.target, "target");
    std::string name = fmt::format("the line {}->{}: gyro grid azimuth against the azimuth of its coordinates", a, b);
    if (reversed) name += fmt::format(" (180 deg apart: from and to swapped? the coordinates give {}->{} {})", a, b,
                                      format_direction_dms(Angle::radians(from_coordinates)));
    else if (gross) name += fmt::format(" (off by {}: a wrong point?)", format_dms(Angle::radians(diff)));
    res_.checks.push_back({std::move(name), diff / units::kArcsecond, limit / units::kArcsecond, CheckUnit::Arcsec,
                           !gross && std::fabs(diff) <= limit, false, true,
                           override_ ? "tolerances.line_coordinates_arcsec in the file"
                                     : "Meridian: the class limit for two independent orientations (the coordinates "
                                       "stand for an orientation of the line); beyond 1 deg always fails",
                           "line.to"});
    if (!res_.checks.back().pass)
      res_.warnings.push_back(fmt::format(
          "the gyro grid azimuth of {}->{} {} differs by {} from the azimuth {} of their coordinates{}", a, b,
          format_direction_dms(Angle::radians(res_.chain.grid_azimuth_rad.value)),
          format_dms(Angle::radians(diff), {1, true, true}), format_direction_dms(Angle::radians(from_coordinates)),
          reversed ? ": line.from and line.to booked the wrong way round?" : ""));
  }

  // The regulations want the same observer above (known line) and below
  // ground (the line); checked where the observers are recorded.
  void check_observers() {
    std::vector<std::string> surface, underground;
    auto collect = [&](const std::vector<DeterminationInput>& v, std::vector<std::string>& out) {
      for (const auto& d : v) {
        const std::string& o = d.observer.empty() ? in_.record.observer : d.observer;
        if (!o.empty() && std::find(out.begin(), out.end(), o) == out.end()) out.push_back(o);
      }
    };
    if (in_.known_line) {
      collect(in_.known_line->before, surface);
      collect(in_.known_line->after, surface);
    }
    collect(in_.line.determinations, underground);
    if (surface.empty() && underground.empty()) {
      res_.notes.push_back("observers not recorded (the regulations want the same observer above and below ground)");
      return;
    }
    std::vector<std::string> all = surface;
    for (const auto& o : underground)
      if (std::find(all.begin(), all.end(), o) == all.end()) all.push_back(o);
    std::string names;
    for (const auto& o : all) names += (names.empty() ? "" : ", ") + o;
    res_.checks.push_back({"the same observer on the known line and on the line (" + names + ")",
                           static_cast<double>(all.size()), 1.0, CheckUnit::Observers, all.size() == 1, false, false,
                           "coal-mine surveying regulations: the same observer above and below ground",
                           "record.observer"});
    if (all.size() > 1) {
      std::string list;
      for (const auto& o : all) list += (list.empty() ? "" : ", ") + o;
      res_.warnings.push_back("more than one observer recorded: " + list);
    }
  }

  // The same observations booked twice (a copied run) count once, not twice.
  void check_duplicated_runs() {
    struct Run {
      std::string name;
      const DeterminationInput* in;
    };
    std::vector<Run> runs;
    auto add = [&](const std::vector<DeterminationInput>& v, const char* what) {
      for (std::size_t i = 0; i < v.size(); ++i) runs.push_back({fmt::format("{}[{}]", what, i), &v[i]});
    };
    if (in_.known_line) {
      add(in_.known_line->before, "known_line.before");
      add(in_.known_line->after, "known_line.after");
    }
    add(in_.line.determinations, "line.determinations");
    std::vector<std::string> pairs;
    std::string second_run;  // the copy, where a checker looks first
    for (std::size_t i = 0; i < runs.size(); ++i)
      for (std::size_t j = i + 1; j < runs.size(); ++j)
        if (same_observations(*runs[i].in, *runs[j].in)) {
          pairs.push_back(runs[i].name + " and " + runs[j].name);
          if (second_run.empty()) second_run = runs[j].name;
        }
    std::string which;
    for (const auto& p : pairs) which += (which.empty() ? " (" : "; ") + p;
    if (!which.empty()) which += ")";
    res_.checks.push_back({"no run booked twice" + which, static_cast<double>(pairs.size()), 0.0, CheckUnit::Runs,
                           pairs.empty(), false, false, "Meridian: identical observations in two runs", second_run});
    for (const auto& p : pairs)
      res_.warnings.push_back(p + " have identical observations: one run was booked twice");
  }

  // Step 3: mean A_G + E → astronomic → geodetic → grid azimuth of C→D.
  void reduce_azimuth_chain() {
    AzimuthChainInput chain;
    chain.gyro_azimuth_rad = res_.gyro_azimuth_mean.mean;
    chain.instrument_constant_rad = res_.instrument_constant_used_rad;
    chain.latitude_rad = res_.station.lat_rad;
    // An E that holds the known station's deflection relates gyro to geodetic
    // azimuths: applying the deflection at the station as well would count
    // it twice.
    const PointDeflection d = e_holds_deflection_ ? PointDeflection{} : deflection_at(in_.line.from, res_.station);
    if (e_holds_deflection_ && (in_.line.from.eta_rad || in_.line.from.xi_rad || deflection_))
      res_.notes.push_back(fmt::format(
          "{}: the deflection of the vertical is not applied: E was calibrated without eta at {} and already "
          "holds the deflection there (give eta at {} as well to apply both)",
          point_label(res_.station, "the station"), point_label(*res_.known_station, "the known station"),
          point_label(*res_.known_station, "the known station")));
    chain.eta_rad = d.eta_rad;
    const bool full = d.xi_rad && d.eta_rad;
    const Sight sight =
        sight_of("line", "line", in_.line.zenith_angle_rad, in_.line.from, res_.station, in_.line.to,
                 res_.target, full);
    if (full) {
      chain.xi_rad = d.xi_rad;
      chain.zenith_distance_rad = sight.zenith_rad;
    }
    chain.convergence_rad = res_.station.grid.convergence_rad;
    if (res_.target)
      chain.arc_to_chord_rad = geodesy::arc_to_chord(grid_, res_.station.grid.x_north_m, res_.station.grid.y_east_m,
                                                     res_.target->grid.x_north_m, res_.target->grid.y_east_m);
    res_.chain = azimuth_chain(chain);
    record_deflection_sources(in_.line.from, res_.station, d, -1.0,
                              res_.chain.zenith_term_applied ? sight.zenith_rad : std::nullopt,
                              res_.chain.geodetic_azimuth_rad.value);
    for (const auto& n : res_.chain.notes) res_.notes.push_back(n);
    note_zenith_term(sight, d, res_.station.name.empty() ? "the station" : res_.station.name,
                     res_.chain.zenith_term_applied, res_.chain.zenith_correction_rad);
  }

  const CampaignInput& in_;
  Progress* progress_;
  const DeflectionModel* deflection_;
  const geodesy::TransverseMercatorGrid grid_;
  std::size_t done_ = 0, total_ = 0;
  RegulationLimits limits_;
  bool e_holds_deflection_ = false;  // E calibrated on a geodetic/grid azimuth without η
  ReduceOptions options_;
  CampaignResult res_;
};

}  // namespace

CampaignResult process(const CampaignInput& in, Progress* progress, const DeflectionModel* deflection) {
  return CampaignRun(in, progress, deflection).run();
}

}  // namespace meridian::gyro
