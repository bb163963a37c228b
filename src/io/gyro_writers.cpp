#include "meridian/io/gyro_writers.hpp"

#include <cmath>
#include <sstream>

#include <fmt/format.h>

#include "meridian/core/dms.hpp"
#include "meridian/core/units.hpp"
#include "gyro_record.hpp"

namespace meridian::io {
namespace {

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
// Fixed-point with 10 decimals (< 1e-4" in degrees or gon), trailing zeros
// dropped: the deg and gon books take no exponents.
std::string decimal(double v) {
  std::string s = fmt::format("{:.10f}", v);
  s.erase(s.find_last_not_of('0') + 1);
  if (s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}
// A circle angle in the book's unit, to 1e-4" or better, as the reader reads it.
std::string circle(double rad, AngleUnit unit) {
  const Angle a = Angle::radians(rad);
  switch (unit) {
    case AngleUnit::Dms: return dms(rad);
    case AngleUnit::Degrees: return decimal(a.deg());
    case AngleUnit::Gon: return decimal(a.gon());
    case AngleUnit::DddMmss: return q(format_ddd_mmss(a, 4));  // quoted: the digits are the value
  }
  return dms(rad);
}
std::string angle_unit_yaml(AngleUnit unit) {
  return unit == AngleUnit::Dms ? std::string() : "angle_unit: " + to_string(unit) + "\n";
}
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
  o += "  scale_value_arcsec: " + num(s.scale_value_rad / units::kArcsecond) + "\n";
  if (s.sigma_scale_value_rad > 0)
    o += "  scale_value_sigma_arcsec: " + num(s.sigma_scale_value_rad / units::kArcsecond) + "\n";
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
    o += "  transit_factor_arcsec_per_div_s: " +
         num(s.transit_factor_rad_per_div_s->value / units::kArcsecond) + "\n";
    if (s.transit_factor_rad_per_div_s->sigma > 0)
      o += "  transit_factor_sigma_arcsec_per_div_s: " +
           num(s.transit_factor_rad_per_div_s->sigma / units::kArcsecond) + "\n";
  }
  o += "  sigma_time_s: " + num(s.sigma_time_s) + "\n";
  o += "  sigma_reading_div: " + num(s.sigma_reading_div) + "\n";
  o += "  accuracy_class_arcsec: " + num(s.accuracy_class_arcsec) + "\n";
}

void determination_yaml(std::string& o, const gyro::DeterminationInput& d, const std::string& ind,
                        AngleUnit unit) {
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
      o += (i ? ", " : "") + circle(d.tracking.reversals_rad[i], unit);
    o += "]\n";
    if (std::isfinite(d.tracking.sigma_reading_rad))
      o += in + "sigma_reading_arcsec: " + num(d.tracking.sigma_reading_rad / units::kArcsecond) +
           "\n";
  } else {
    const auto& n = d.nontracking;
    o += in + "clamp_reading: " + circle(d.clamp_reading_rad, unit) + "\n";
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
    o += in + "target_reading: " + circle(d.target_reading_rad->value, unit) + "\n";
    if (d.target_reading_rad->sigma > 0)
      o += in + "target_sigma_arcsec: " + num(d.target_reading_rad->sigma / units::kArcsecond) +
           "\n";
  }
  if (!d.target_rounds.empty()) {
    o += in + "target_rounds:\n";
    for (const auto& r : d.target_rounds)
      o += in + "  - {when: " + (r.when == gyro::TargetRound::When::Before ? "before" : "after") +
           ", left: " + circle(r.face_left_rad, unit) + ", right: " + circle(r.face_right_rad, unit) + "}\n";
    if (!d.target_reading_rad && d.target_round_sigma_rad > 0)
      o += in + "target_sigma_arcsec: " + num(d.target_round_sigma_rad / units::kArcsecond) + "\n";
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
    o += in + "eta_arcsec: " + num(p.eta_rad->value / units::kArcsecond) + "\n";
    if (p.eta_rad->sigma > 0)
      o += in + "eta_sigma_arcsec: " + num(p.eta_rad->sigma / units::kArcsecond) + "\n";
  }
  if (p.height_m) o += in + "height_m: " + num(*p.height_m) + "\n";
  if (p.xi_rad) {
    o += in + "xi_arcsec: " + num(p.xi_rad->value / units::kArcsecond) + "\n";
    if (p.xi_rad->sigma > 0)
      o += in + "xi_sigma_arcsec: " + num(p.xi_rad->sigma / units::kArcsecond) + "\n";
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
  o += angle_unit_yaml(in.angle_unit);
  instrument_yaml(o, in.instrument);
  o += "station:\n  latitude_deg: " + num(in.latitude_rad / units::kDegree) + "\n";
  o += "determinations:\n";
  for (const auto& d : in.determinations) determination_yaml(o, d, "  ", in.angle_unit);
  return o;
}

std::string campaign_file_yaml(const gyro::CampaignInput& c, const std::string& header) {
  std::string o = comment_block(header);
  if (!c.name.empty()) o += "campaign: " + q(c.name) + "\n";
  o += angle_unit_yaml(c.angle_unit);
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
    if (k.zenith_angle_rad) o += "  zenith_angle: " + circle(*k.zenith_angle_rad, c.angle_unit) + "\n";
    o += "  azimuth: {kind: " + geodesy::to_string(k.azimuth.kind) +
         ", value: " + circle(k.azimuth.value_rad.value, c.angle_unit) +
         ", sigma_arcsec: " + num(k.azimuth.value_rad.sigma / units::kArcsecond) + "}\n";
    if (!k.before.empty()) {
      o += "  before:\n";
      for (const auto& d : k.before) determination_yaml(o, d, "    ", c.angle_unit);
    }
    if (!k.after.empty()) {
      o += "  after:\n";
      for (const auto& d : k.after) determination_yaml(o, d, "    ", c.angle_unit);
    }
  }
  if (c.instrument_constant_rad)
    o += "instrument_constant: {value: " + circle(c.instrument_constant_rad->value, c.angle_unit) +
         ", sigma_arcsec: " + num(c.instrument_constant_rad->sigma / units::kArcsecond) + "}\n";
  o += "line:\n";
  point_yaml(o, "from", c.line.from, "  ");
  if (c.line.to) point_yaml(o, "to", *c.line.to, "  ");
  if (c.line.zenith_angle_rad) o += "  zenith_angle: " + circle(*c.line.zenith_angle_rad, c.angle_unit) + "\n";
  o += "  determinations:\n";
  for (const auto& d : c.line.determinations) determination_yaml(o, d, "    ", c.angle_unit);
  std::string tol;
  for (const auto& f : detail::tolerance_fields(c.tolerances))
    if (*f.member) tol += std::string("  ") + f.key + ": " + num(**f.member / f.unit) + "\n";
  if (!tol.empty()) o += "tolerances:\n" + tol;
  if (c.gravity_model)
    o += "gravity_model: {model: " + q(c.gravity_model->source) +
         (c.gravity_model->max_degree >= 0
              ? ", max_degree: " + std::to_string(c.gravity_model->max_degree)
              : "") +
         ", eta_sigma_arcsec: " + num(c.gravity_model->sigma_eta_rad / units::kArcsecond) +
         ", xi_sigma_arcsec: " + num(c.gravity_model->sigma_xi_rad / units::kArcsecond) + "}\n";
  return o;
}

namespace {

// "Simulated by: <command line>" and the truth, one line each (comment_block makes them comments).
std::string simulation_header(const std::string& command_line, const std::vector<std::string>& truth) {
  std::string h = "Simulated by: " + command_line + "\n";
  for (const auto& t : truth) h += t + "\n";
  return h;
}

}  // namespace

std::string simulated_book_yaml(const SimulatedBook& s) {
  if (const auto* c = std::get_if<gyro::SimulatedCampaign>(&s.book))
    return campaign_file_yaml(c->input, simulation_header(s.command_line, c->truth));
  const auto& station = std::get<gyro::SimulatedStation>(s.book);
  return reduce_file_yaml(station.input, simulation_header(s.command_line, station.truth));
}

// The templates are hand-written field books (not generated), so that every
// line can carry its comment; the parts both kinds share are written once.
// Their numbers come from simulated runs (tau 600"/div, lambda 0.21, T_B
// 424 s, 0.15 s stopwatch) with target readings chosen for E = +18";
// tests/io checks that they read back and tests/cli that they process with
// every check passing.
namespace tmpl {

constexpr const char* kBookingHabits = R"yaml(# Booking habits accepted:
# * times in seconds (279.6) or as the stopwatch shows them, "4:39.6" (m:ss.s)
#   or "1:04:39.6" (h:mm:ss.s); quote them so every YAML tool keeps the text;
# * circle angles in the unit named by angle_unit (below), never guessed;
# * scale readings in divisions, positive towards east (see "Booking the
#   oscillation" for how your eyepiece shows it).

)yaml";

constexpr const char* kAngleUnit = R"yaml(angle_unit: dms        # how circle angles are booked (clamp_reading, reversals, target_reading,
                       # and in campaigns known_line.azimuth.value, instrument_constant.value):
                       #   dms      (the default) a number is decimal degrees, text is D M S:
                       #            "63°27′24.9″", "63 27 24.9", "63:27:24.9"
                       #   deg      decimal degrees: 63.456917
                       #   gon      decimal gon (400 to the circle): 70.5077
                       #   ddd.mmss calculator notation: 63.27249 = 63°27′24.9″
                       # Fields named *_deg (latitudes, longitudes) are always degrees or DMS
                       # text, fields named *_arcsec always arc-seconds, whatever angle_unit says.

)yaml";

constexpr const char* kInstrument = R"yaml(instrument:
  name: "GAK1-type gyro attachment No. 0000 on a 2\" theodolite"   # free text
  scale_value_arcsec: 600           # tau: value of one scale division (arcsec/div); required
  # scale_value_sigma_arcsec: 2     # sigma of tau (arcsec/div)
  torsion_ratio: 0.21               # lambda = D_B/D_K, tape torsion over directive torque (零位改正系数)
  torsion_ratio_sigma: 0.002        # its sigma (dimensionless)
  # periods:                        # instead of torsion_ratio: lambda from periods (s or "m:ss.s")
  #   tracking_s: "7:46.4"          #   T_A, tracking period
  #   nontracking_s: "7:04.0"       #   T_B, non-tracking period: lambda = (T_A/T_B)^2 - 1
  #   # free_s: "16:57.0"           #   T_F, motor off: lambda = (T_A/T_F)^2 (instead of nontracking_s)
  #   sigma_s: 0.5                  #   sigma of each period (s)
  constants_latitude_deg: 35.8      # latitude where lambda (or the periods, c) was determined (deg);
                                    # lambda is rescaled to each station: lambda0 cos(phi0)/cos(phi)
  # transit_factor_arcsec_per_div_s: 2.69        # calibrated transit factor c (arcsec per div.s),
  # transit_factor_sigma_arcsec_per_div_s: 0.01  # from `meridian gyro transit-factor`
  sigma_time_s: 0.15                # sigma of one stopwatch time (s); default 0.1
  sigma_reading_div: 0.05           # sigma of one scale reading (div); default 0.05
  accuracy_class_arcsec: 15         # class of the instrument (arcsec); sets the default limits
                                    # (15: 40" between runs, 25: 70")
  # latitude_limit_deg: 75          # stations above this |latitude| (deg) are refused; default 75

)yaml";

constexpr const char* kCampaignHead = R"yaml(# Gyro field book: a whole orientation job (`meridian gyro template`).
#
# Copy this file, replace the example values with your own bookings and run
#     meridian gyro campaign FILE               (add --strict to fail on a check)
# The example job is invented but consistent, so it runs as it stands.
# Every field is explained beside it with its unit; delete what you do not use.
# Reference: docs/file-formats.md (fields), docs/gyro-theodolite.md (methods,
# signs, checks, and "Booking the oscillation" for your instrument's scale).
#
# Programme of the coal-mine surveying regulations (三、二、三): the instrument
# constant on the known surface line 3 times before going underground
# (known_line.before), the underground line 2 times (line.determinations),
# the known line 3 times after coming up (known_line.after). The example
# books both modes: tracking (reversal points) and non-tracking (transit).
#
)yaml";

constexpr const char* kCampaignTitle = R"yaml(campaign: "Example colliery - main decline P1-P2"   # title of the job, printed on the report
record:                             # the record sheet (free text, printed on the result sheet)
  observer: "A. Observer"           # the regulations want the same observer above and below ground;
                                    # a run may name its own (observer: in the run)
  booker: "B. Booker"
  computed_by: "C. Computer"
  checked_by: "D. Checker"
  date: "2026-11-28"
  weather: "surface overcast, wind 2 m/s; underground 1.2 m/s at the station"
  temperature: "surface 6 C, underground 24 C"
  # remarks: "..."
# stochastic_model: white           # how the reversal readings of tracking runs are weighted for N_G:
                                    # white (the default: independent readings) | markov1 | markov2 |
                                    # recommended (correlated errors fitted to the run's own readings;
                                    # needs >= 6 reversals per run, else white with a warning). A run
                                    # may give its own. See docs/gyro-stochastic.md
)yaml";

constexpr const char* kCampaignRest = R"yaml(grid:                               # the plane grid of the coordinates below
  system: gk3                       # gk3 | gk6 | utm | custom
  zone: 38                          # zone number (gk3 zone 38: central meridian 114 E)
  ellipsoid: CGCS2000               # WGS84 | GRS80 | CGCS2000 | Krassovsky1940 | IAG75
  # zone_prefix: true               # eastings carry the zone number (38 427 811.205 m)
  # hemisphere: north               # utm only
  # central_meridian_deg, scale_factor, false_easting_m, false_northing_m: system custom only

known_line:                         # surface line of known azimuth: calibrates the instrument constant E
  # Points: grid x_m (north) and y_m (east) in metres, or latitude_deg/longitude_deg;
  # height_m ellipsoidal height (m); eta_arcsec the deflection of the vertical in the
  # prime vertical (astronomic minus geodetic, arcsec) with its sigma, when known.
  from: {name: K1, x_m: 3963512.384, y_m: 427811.205, height_m: 96.3, eta_arcsec: -3.1, eta_sigma_arcsec: 1.0}
  to:   {name: K2, x_m: 3964247.981, y_m: 428628.617, height_m: 102.8}
  azimuth:                          # the given azimuth K1 -> K2
    kind: grid                      # grid (坐标方位角) | geodetic | astronomic
    value: "48°00′56.3″"            # angle_unit
    sigma_arcsec: 3                 # its sigma (arcsec)
  before:                           # 3 runs before going underground
    - mode: tracking                # tracking: the light mark is followed with the slow-motion screw
      label: "K1-K2 before 1 (tracking)"   # free text, shown in the report
      time: "08:40"
      method: schuler               # tracking: two-point | schuler | lsq-linear | lsq | all
      # horizontal-circle readings at the reversals (turning points), in time order (angle_unit)
      reversals: ["359°17′00″", "1°46′13″", "359°17′32″", "1°45′32″", "359°18′07″"]
      sigma_reading_arcsec: 5       # a-priori sigma of one reversal reading (arcsec); without it the
                                    # class/3 default only checks the readings
      zero_position:                # motor-off runs: the tape zero, before and after the gyro run
        before: {reversals_div: [4.1, -3.6, 3.9, -3.4, 3.7]}   # scale readings at the reversals (div, east +)
        after:  {reversals_div: [-3.7, 4.0, -3.5, 3.8, -3.3]}  # optional times_s: [...] (s or "m:ss.s")
      # zero_position_div: 0.15     # instead of the runs: the tape zero alpha_p given (div)
      target_rounds:                # the rounds (测回), face left (盘左) and face right (盘右), before
                                    # and after the run (angle_unit); their mean (L + R - 180)/2 is the
                                    # target reading, 2C = L - (R - 180) is shown and checked
        - {when: before, left: "48°03′48.6″", right: "228°03′57.6″"}
        - {when: after,  left: "48°03′49.6″", right: "228°03′58.6″"}
      target_sigma_arcsec: 2        # sigma of one round's direction (arcsec)
    - mode: non-tracking            # non-tracking: alidade clamped near north, the oscillation is timed
      label: "K1-K2 before 2 (transit)"
      time: "09:15"
      method: transit               # transit | time-difference | direct | timed-amplitude-1 |
                                    # timed-amplitude-2 | lsq | all
      clamp_reading: "0°28′00″"     # N', circle reading of the clamped alidade (angle_unit)
      period_s: "7:04.0"            # T_B, non-tracking period (s or "m:ss.s"); optional for transit
      # period_sigma_s: 0.5         # its sigma (s)
      crossings:                    # passages of the light mark through a graduation
        - level_div: 0              # the graduation (div); 0 is the scale centre
          first_direction: east     # motion at the first time: east (东, the reading increasing) or
                                    # west (西, decreasing). Whether east is 向右 or 向左 as the crew
                                    # sees the mark depends on the eyepiece: do the sign test once
                                    # (docs/gyro-theodolite.md 14.3) and note it here, e.g.
                                    # "this instrument: east = 向左 (mark moving left)"
          times_s: ["0:34.8", "4:11.6", "7:38.3"]   # stopwatch times, increasing
      reversals_div: [9.5, -8.8]    # scale readings at the reversals (div, east +), in time order
      # reversal_times_s: ["2:21.0", "5:53.5"]   # optional, one per reversal reading
      # sigma_time_s: 0.2           # optional, overrides the instrument's sigma for this run
      zero_position:
        before: {reversals_div: [3.6, -3.9, 3.4, -3.7, 3.2]}
        after:  {reversals_div: [3.7, -3.8, 3.5, -3.6, 3.3]}
      target_rounds:
        - {when: before, left: "48°04′52.0″", right: "228°05′01.0″"}
        - {when: after,  left: "48°04′53.0″", right: "228°05′02.0″"}
      target_sigma_arcsec: 2
    - mode: tracking
      label: "K1-K2 before 3 (tracking)"
      time: "09:50"
      method: schuler
      reversals: ["179°57′29″", "182°26′50″", "179°58′21″", "182°26′06″", "179°58′47″"]
      sigma_reading_arcsec: 5
      zero_position:
        before: {reversals_div: [-3.8, 4.1, -3.6, 3.9, -3.4]}
        after:  {reversals_div: [4.0, -3.7, 3.8, -3.5, 3.6]}
      target_rounds:
        - {when: before, left: "228°44′33.8″", right: "48°44′42.8″"}
        - {when: after,  left: "228°44′34.8″", right: "48°44′43.8″"}
      target_sigma_arcsec: 2
  after:                            # 3 runs after coming up
    - mode: tracking
      label: "K1-K2 after 1 (tracking)"
      time: "14:45"
      method: schuler
      reversals: ["268°50′44″", "271°19′52″", "268°51′26″", "271°19′16″", "268°52′09″"]
      sigma_reading_arcsec: 5
      zero_position:
        before: {reversals_div: [3.9, -3.8, 3.7, -3.6, 3.5]}
        after:  {reversals_div: [4.1, -3.7, 3.9, -3.5, 3.7]}
      target_rounds:
        - {when: before, left: "317°37′47.4″", right: "137°37′56.4″"}
        - {when: after,  left: "317°37′48.4″", right: "137°37′57.4″"}
      target_sigma_arcsec: 2
    - mode: non-tracking
      label: "K1-K2 after 2 (transit)"
      time: "15:20"
      method: transit
      clamp_reading: "270°00′00″"
      period_s: "7:04.0"
      crossings:
        - {level_div: 0, first_direction: east, times_s: ["0:41.4", "4:18.3", "7:45.7"]}
      reversals_div: [9.5, -8.9]
      zero_position:
        before: {reversals_div: [-3.6, 3.9, -3.5, 3.8, -3.3]}
        after:  {reversals_div: [3.9, -3.5, 3.7, -3.4, 3.6]}
      target_rounds:
        - {when: before, left: "317°36′09.6″", right: "137°36′18.6″"}
        - {when: after,  left: "317°36′10.6″", right: "137°36′19.6″"}
      target_sigma_arcsec: 2
    - mode: tracking
      label: "K1-K2 after 3 (tracking)"
      time: "15:55"
      method: schuler
      reversals: ["44°08′07″", "46°37′09″", "44°08′46″", "46°36′39″", "44°09′22″"]
      sigma_reading_arcsec: 5
      zero_position:
        before: {reversals_div: [-4.0, 3.7, -3.8, 3.5, -3.6]}
        after:  {reversals_div: [-3.9, 3.7, -3.7, 3.6, -3.5]}
      target_rounds:
        - {when: before, left: "92°55′26.0″", right: "272°55′35.0″"}
        - {when: after,  left: "92°55′27.0″", right: "272°55′36.0″"}
      target_sigma_arcsec: 2
# Instead of known_line, an instrument constant determined earlier:
# instrument_constant: {value: "0 00 18.0", sigma_arcsec: 5}   # E (angle_unit), its sigma (arcsec)

line:                               # the line to orient: from the gyro station to its target
  from: {name: P1, x_m: 3963321.552, y_m: 428105.330, height_m: -412.5, eta_arcsec: -3.3, eta_sigma_arcsec: 1.0}
  to:   {name: P2, x_m: 3963200.752, y_m: 428000.330, height_m: -415.1}   # optional: gives the arc-to-chord term
  determinations:                   # 2 runs underground
    - mode: tracking
      label: "P1-P2 1 (tracking)"
      time: "11:30"                 # clock time of the run (record sheet)
      method: schuler
      reversals: ["88°32′31″", "91°01′36″", "88°33′08″", "91°00′56″", "88°33′40″"]
      sigma_reading_arcsec: 5
      zero_position:
        before: {reversals_div: [-3.5, 3.9, -3.3, 3.7, -3.2]}
        after:  {reversals_div: [4.0, -3.4, 3.8, -3.3, 3.6]}
      target_rounds:                # rounds booked to the second, as a DJ2 reads them
        - {when: before, left: "310°18′17″", right: "130°18′26″"}
        - {when: after,  left: "310°18′18″", right: "130°18′26″"}
      target_sigma_arcsec: 2
      # target_reading: "310°18′21.8″"  # instead of target_rounds: the circle reading to the target, the
      #                                 # mean of face left and face right (angle_unit), with target_sigma_arcsec
    - mode: non-tracking            # five transits and four reversal readings
      label: "P1-P2 2 (transit)"
      time: "12:20"
      method: transit
      clamp_reading: "89°50′00″"
      period_s: "7:04.0"
      crossings:
        - {level_div: 0, first_direction: east, times_s: ["1:03.2", "4:31.3", "8:06.7", "11:35.0", "15:11.0"]}
      reversals_div: [8.8, -9.4, 8.7, -9.2]
      zero_position:
        before: {reversals_div: [3.8, -3.6, 3.6, -3.4, 3.4]}
        after:  {reversals_div: [3.7, -3.7, 3.5, -3.5, 3.3]}
      target_rounds:
        - {when: before, left: "310°18′24.5″", right: "130°18′33.5″"}
        - {when: after,  left: "310°18′25.5″", right: "130°18′34.5″"}
      target_sigma_arcsec: 2

# tolerances:                       # optional: the limits of the coal-mine surveying regulations follow
#                                   # accuracy_class_arcsec (docs/gyro-theodolite.md, "Checks"). Write a
#                                   # key here only where the job is held to another limit than its
#                                   # class's (the values shown are the 15" class's):
  # determination_difference_arcsec: 40       # any two runs on the line (15" class 40", 25" class 70")
  # instrument_constant_difference_arcsec: 40 # any two instrument constants, and their before/after means
  # instrument_constant_means_arcsec: 40      # the before/after means alone
  # zero_position_div: 0.5                    # tape zero, after minus before a run (div)
  # zero_position_limit_div: 0.5              # |tape zero| of every motor-off run (div)
  # orientation_difference_arcsec: 40         # two independent orientations (`gyro orientations`)
  # orientation_mean_sigma_arcsec: 10         # sigma of their mean
  # known_azimuth_coordinates_arcsec: 0.75    # given known azimuth against its coordinates (grid: their rounding)
  # line_coordinates_arcsec: 40               # the line's gyro azimuth against its coordinates (gyro - traverse)
  # instrument_constant_max_arcsec: 600       # |E| plausible

# options:                          # optional
#   zero_position_method: schuler   # how the tape zero is taken from its reversals:
#                                   # two-point | schuler | lsq-linear | lsq
#   zero_position_tolerance_div: 0.5
#   estimate_damping: false         # unified fit (method lsq): also estimate the damping
# gravity_model:                    # optional: eta where a point gives no eta_arcsec
#   model: egm2008                  # a .gfc/.egm file beside this one, or a GeographicLib model name
#   eta_sigma_arcsec: 1.5
)yaml";

constexpr const char* kReduceHead = R"yaml(# Gyro field book: the runs of one station (`meridian gyro template --kind reduce`).
#
# Copy this file, replace the example values with your own bookings and run
#     meridian gyro reduce FILE
# to get gyro north N_G (the circle reading of north) of every run with its
# sigma. For a whole orientation job (known line, 3-2-3 programme, grid
# azimuth) start from `meridian gyro template` instead.
# The example runs are invented but consistent, so the file runs as it stands.
# Every field is explained beside it with its unit; delete what you do not use.
# Reference: docs/file-formats.md (fields), docs/gyro-theodolite.md (methods,
# signs, and "Booking the oscillation" for your instrument's scale).
#
)yaml";

constexpr const char* kReduceRest = R"yaml(station:
  name: "P1"                        # free text
  latitude_deg: "35 47 49.6"        # geodetic latitude of the station (deg or DMS text)

determinations:
  - mode: tracking                  # tracking: the light mark is followed with the slow-motion screw
    label: "P1 run 1 (tracking) 11:30"   # free text, shown in the report
    method: all                     # tracking: two-point | schuler | lsq-linear | lsq | all
    # horizontal-circle readings at the reversals (turning points), in time order (angle_unit)
    reversals: ["88°32′31″", "91°01′36″", "88°33′08″", "91°00′56″", "88°33′40″"]
    # sigma_reading_arcsec: 5       # a-priori sigma of one reversal reading (arcsec); optional
    zero_position:                  # motor-off runs: the tape zero, before and after the gyro run
      before: {reversals_div: [-3.5, 3.9, -3.3, 3.7, -3.2]}   # scale readings at the reversals (div, east +)
      after:  {reversals_div: [4.0, -3.4, 3.8, -3.3, 3.6]}   # optional times_s: [...] (s or "m:ss.s")
    # zero_position_div: 0.15       # instead of the runs: the tape zero alpha_p given (div)
    # target_reading: "310°18′21.7″"   # circle reading to the target (angle_unit); used by campaigns

  - mode: non-tracking              # non-tracking: alidade clamped near north, the oscillation is timed
    label: "P1 run 2 (three levels) 12:20"
    method: all                     # transit | time-difference | direct | timed-amplitude-1 |
                                    # timed-amplitude-2 | lsq | all (every method that applies)
    clamp_reading: "89°50′00″"      # N', circle reading of the clamped alidade (angle_unit)
    period_s: "7:04.0"              # T_B, non-tracking period (s or "m:ss.s"); some methods need it
    # period_sigma_s: 0.5           # its sigma (s)
    crossings:                      # passages of the light mark through a graduation
      - level_div: -2               # the graduation (div); 0 is the scale centre, west negative
        first_direction: east       # motion at the first time: east (reading increasing) or west
        times_s: ["0:39.4", "4:36.8", "7:43.2"]   # stopwatch times, increasing
      - {level_div: 0, first_direction: east, times_s: ["0:53.8", "4:22.1", "7:57.9"]}
      - {level_div: 2, first_direction: east, times_s: ["1:08.9", "4:06.8", "8:13.0"]}
    reversals_div: [8.9, -9.5]      # scale readings at the reversals (div, east +), in time order
    # reversal_times_s: ["2:38", "6:10"]   # optional, one per reversal reading (s or "m:ss.s")
    # sigma_time_s: 0.2             # optional, overrides the instrument's sigma for this run
    zero_position:
      before: {reversals_div: [3.8, -3.6, 3.6, -3.4, 3.4]}
      after:  {reversals_div: [3.7, -3.7, 3.5, -3.5, 3.3]}

# options:                          # optional
#   zero_position_method: schuler   # how the tape zero is taken from its reversals:
#                                   # two-point | schuler | lsq-linear | lsq
#   zero_position_tolerance_div: 0.5   # limit of the tape zero's drift, after minus before (div)
#   estimate_damping: false         # unified fit (method lsq): also estimate the damping
)yaml";

}  // namespace tmpl

std::string campaign_template_yaml() {
  using namespace tmpl;
  return std::string(kCampaignHead) + kBookingHabits + kCampaignTitle + kAngleUnit + kInstrument +
         kCampaignRest;
}

std::string reduce_template_yaml() {
  using namespace tmpl;
  return std::string(kReduceHead) + kBookingHabits + kAngleUnit + kInstrument + kReduceRest;
}

}  // namespace meridian::io
