#include "meridian/io/gyro_files.hpp"

#include <cmath>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/geodesy/ellipsoid.hpp"
#include "meridian/geodesy/frames.hpp"
#include "meridian/geodesy/grid.hpp"
#include "meridian/geodesy/laplace.hpp"
#include "meridian/io/document.hpp"
#include "meridian/io/source_map.hpp"
#include "gravity_model_ref.hpp"
#include "gyro_record.hpp"

namespace meridian::io {
namespace {

using gyro::Uncertain;

// A duration booked with a stopwatch (seconds or m:ss.s), > 0.
double positive_time_s(const Node& n) {
  const double v = n.time_s();
  if (!(v > 0)) n.fail(fmt::format("must be positive (got {})", v));
  return v;
}

// Stopwatch times of one run, strictly increasing; a time out of order is
// reported at its own element.
std::vector<double> increasing_times_s(const Node& n) {
  const std::vector<Node> e = n.elements();
  std::vector<double> t;
  for (const auto& x : e) t.push_back(x.time_s());
  for (std::size_t i = 1; i < t.size(); ++i)
    if (!(t[i] > t[i - 1]))
      e[i].fail(
          fmt::format("times must increase (t{} = {} <= t{} = {})", i + 1, t[i], i, t[i - 1]));
  return t;
}

// The file's angle_unit (default dms: numbers are degrees, text is DMS).
AngleUnit read_angle_unit(const Node& root) {
  const auto v = root.get("angle_unit");
  if (!v) return AngleUnit::Dms;
  try {
    return angle_unit_from_string(v->string());
  } catch (const Error& e) {
    v->fail(e.message());
  }
}

// "value" and "value_sigma"-style pairs: a σ key is optional.
double sigma_or(const Node& n, const std::string& key, double fallback) {
  auto s = n.get(key);
  return s ? s->non_negative_number() : fallback;
}

gyro::InstrumentSpec read_instrument(const Node& n) {
  n.allow_only({"name", "serial", "scale_value_arcsec", "scale_value_sigma_arcsec", "torsion_ratio",
                "torsion_ratio_sigma", "constants_latitude_deg", "periods",
                "transit_factor_arcsec_per_div_s", "transit_factor_sigma_arcsec_per_div_s",
                "sigma_time_s", "sigma_reading_div", "latitude_limit_deg",
                "accuracy_class_arcsec"});
  gyro::InstrumentSpec s;
  if (auto v = n.get("name")) s.name = v->string();
  if (auto v = n.get("serial")) s.serial = v->string();
  s.scale_value_rad = n.require("scale_value_arcsec").positive_number() * units::kArcsecond;
  s.sigma_scale_value_rad = sigma_or(n, "scale_value_sigma_arcsec", 0.0) * units::kArcsecond;
  if (auto v = n.get("torsion_ratio")) {
    const double lam = v->non_negative_number();
    s.torsion_ratio = Uncertain{lam, sigma_or(n, "torsion_ratio_sigma", 0.0)};
  } else if (n.has("torsion_ratio_sigma")) {
    n.require("torsion_ratio_sigma").fail("torsion_ratio_sigma given without torsion_ratio");
  }
  if (auto p = n.get("periods")) {
    p->allow_only({"tracking_s", "nontracking_s", "free_s", "sigma_s"});
    const double sig = sigma_or(*p, "sigma_s", 0.0);
    if (auto v = p->get("tracking_s")) s.tracking_period_s = Uncertain{positive_time_s(*v), sig};
    if (auto v = p->get("nontracking_s"))
      s.nontracking_period_s = Uncertain{positive_time_s(*v), sig};
    if (auto v = p->get("free_s")) s.free_period_s = Uncertain{positive_time_s(*v), sig};
  }
  if (auto v = n.get("constants_latitude_deg")) s.constants_latitude_rad = v->angle().rad();
  if (auto v = n.get("transit_factor_arcsec_per_div_s"))
    s.transit_factor_rad_per_div_s =
        Uncertain{v->positive_number() * units::kArcsecond,
                  sigma_or(n, "transit_factor_sigma_arcsec_per_div_s", 0.0) * units::kArcsecond};
  if (auto v = n.get("sigma_time_s")) s.sigma_time_s = v->positive_number();
  if (auto v = n.get("sigma_reading_div")) s.sigma_reading_div = v->positive_number();
  if (auto v = n.get("latitude_limit_deg")) {
    const double d = v->positive_number();
    if (d >= 90.0) v->fail("the latitude limit must be below 90 deg");
    s.latitude_limit_rad = d * units::kDegree;
  }
  if (auto v = n.get("accuracy_class_arcsec")) s.accuracy_class_arcsec = v->positive_number();
  else s.accuracy_class_booked = false;
  return s;
}

gyro::ZeroPositionRun read_zero_run(const Node& n) {
  n.allow_only({"reversals_div", "times_s"});
  gyro::ZeroPositionRun r;
  r.reversals_div = n.require("reversals_div").numbers();
  if (auto t = n.get("times_s")) r.times_s = increasing_times_s(*t);
  return r;
}

// A direction (circle reading or azimuth) as booked, in [0, full circle): a value beyond it is
// refused, not wrapped, since 399 47 00 in a degrees book is a gon value or a slip, never an
// azimuth (helper trial, issue 36: it was taken as 39 47 00). Negative values wrap.
Angle read_circle_direction(const Node& n, AngleUnit unit) {
  const Angle a = n.angle(unit);
  const double full = 2.0 * units::kPi;
  if (a.rad() > full * (1.0 + 1e-15)) {
    const bool gon_like = unit != AngleUnit::Gon && a.rad() < 400.0 / 360.0 * full * (1.0 + 1e-15);
    n.fail(fmt::format("a direction is less than a full circle ({}): \"{}\" is {:.6f} deg{}",
                       unit == AngleUnit::Gon ? "400 gon" : "360 deg", n.string(), a.deg(),
                       gon_like ? ": a gon value in a book whose angle_unit is not gon?" : ""));
  }
  return a.normalized_positive();
}

int read_direction(const Node& n) {
  const std::string s = n.string();
  if (s == "east" || s == "e" || s == "+" || s == "+1" || s == "1") return +1;
  if (s == "west" || s == "w" || s == "-" || s == "-1") return -1;
  n.fail(fmt::format("expected east or west, got \"{}\"", s));
}

// `stochastic_model:` (campaign files).
gyro::StochasticChoice read_stochastic_choice(const Node& v) {
  try {
    return gyro::stochastic_choice_from_string(v.string());
  } catch (const InputError& e) {
    v.fail(e.message());
  }
}

gyro::Mode read_mode(const Node& mode) {
  const std::string m = mode.string();
  if (m == "non-tracking" || m == "nontracking") return gyro::Mode::NonTracking;
  if (m == "tracking") return gyro::Mode::Tracking;
  mode.fail(fmt::format("unknown mode \"{}\" (expected tracking or non-tracking)", m));
}

// The tracking run: its circle readings at the reversal points (in the file's `unit`).
void read_tracking_run(const Node& n, AngleUnit unit, gyro::DeterminationInput& d) {
  for (const char* k : {"clamp_reading", "period_s", "crossings", "reversals_div", "reversal_times_s"})
    if (auto v = n.get(k)) v->fail("field of a non-tracking determination given for mode tracking");
  const Node rev = n.require("reversals");
  for (const auto& e : rev.elements()) d.tracking.reversals_rad.push_back(e.angle(unit).rad());
  if (auto v = n.get("sigma_reading_arcsec")) d.tracking.sigma_reading_rad = v->positive_number() * units::kArcsecond;
}

gyro::Crossing read_crossing(const Node& e) {
  e.allow_only({"level_div", "times_s", "first_direction"});
  gyro::Crossing x;
  x.level_div = e.require("level_div").number();
  const Node times = e.require("times_s");
  x.times_s = increasing_times_s(times);
  if (x.times_s.empty()) times.fail("no crossing times");
  x.first_direction = read_direction(e.require("first_direction"));
  return x;
}

// The non-tracking run: the clamp reading (in the file's `unit`), timed crossings, reversal
// readings, with the instrument's σ unless the run books its own.
void read_nontracking_run(const Node& n, const gyro::InstrumentSpec& inst, AngleUnit unit,
                          gyro::DeterminationInput& d) {
  for (const char* k : {"reversals", "sigma_reading_arcsec"})
    if (auto v = n.get(k)) v->fail("field of a tracking determination given for mode non-tracking");
  d.clamp_reading_rad = n.require("clamp_reading").angle(unit).rad();
  auto& o = d.nontracking;
  o.sigma_time_s = inst.sigma_time_s;
  o.sigma_reading_div = inst.sigma_reading_div;
  if (auto v = n.get("sigma_time_s")) o.sigma_time_s = v->positive_number();
  if (auto v = n.get("sigma_reading_div")) o.sigma_reading_div = v->positive_number();
  if (auto v = n.get("period_s")) o.period_s = Uncertain{positive_time_s(*v), sigma_or(n, "period_sigma_s", 0.0)};
  if (auto c = n.get("crossings"))
    for (const auto& e : c->elements()) o.crossings.push_back(read_crossing(e));
  if (auto v = n.get("reversals_div")) o.reversals_div = v->numbers();
  if (auto v = n.get("reversal_times_s")) {
    o.reversal_times_s = increasing_times_s(*v);
    if (o.reversal_times_s.size() != o.reversals_div.size())
      v->fail(fmt::format("{} reversal times for {} reversal readings", o.reversal_times_s.size(),
                          o.reversals_div.size()));
  }
  if (o.crossings.empty() && o.reversals_div.empty())
    n.fail("a non-tracking determination needs crossings and/or reversals_div");
}

// The zero position: given directly, or from motor-off runs before and/or after.
void read_zero_position(const Node& n, gyro::DeterminationInput& d) {
  if (auto v = n.get("zero_position_div")) {
    if (n.has("zero_position")) v->fail("give zero_position_div or zero_position runs, not both");
    d.zero_position = Uncertain{v->number(), sigma_or(n, "zero_position_sigma_div", 0.0)};
  }
  if (auto z = n.get("zero_position")) {
    z->allow_only({"before", "after"});
    if (auto b = z->get("before")) d.zero_before = read_zero_run(*b);
    if (auto a = z->get("after")) d.zero_after = read_zero_run(*a);
    if (!d.zero_before && !d.zero_after) z->fail("give a before and/or an after run");
  }
}

gyro::TargetRound read_target_round(const Node& r, AngleUnit unit) {
  r.allow_only({"when", "left", "right"});
  gyro::TargetRound t;
  const Node when = r.require("when");
  const std::string w = when.string();
  if (w == "before") t.when = gyro::TargetRound::When::Before;
  else if (w == "after") t.when = gyro::TargetRound::When::After;
  else when.fail(fmt::format("expected before or after, got \"{}\"", w));
  t.face_left_rad = read_circle_direction(r.require("left"), unit).rad();
  t.face_right_rad = read_circle_direction(r.require("right"), unit).rad();
  return t;
}

// The circle reading to the target, and/or the rounds it is reduced from.
void read_target(const Node& n, AngleUnit unit, gyro::DeterminationInput& d) {
  if (auto v = n.get("target_reading"))
    d.target_reading_rad = Uncertain{read_circle_direction(*v, unit).rad(),
                                     sigma_or(n, "target_sigma_arcsec", 0.0) * units::kArcsecond};
  if (auto rounds = n.get("target_rounds")) {
    for (const Node& r : rounds->elements()) d.target_rounds.push_back(read_target_round(r, unit));
    if (d.target_rounds.empty()) rounds->fail("give at least one round");
    d.target_round_sigma_rad = sigma_or(n, "target_sigma_arcsec", 0.0) * units::kArcsecond;
  }
}

// Circle angles (clamp, reversals, target) are in the file's `unit`.
gyro::DeterminationInput read_determination(const Node& n, const gyro::InstrumentSpec& inst,
                                            AngleUnit unit) {
  n.allow_only({"label", "mode", "method", "clamp_reading", "period_s", "period_sigma_s",
                "zero_position_div", "zero_position_sigma_div", "zero_position", "crossings",
                "reversals_div", "reversal_times_s", "sigma_time_s", "sigma_reading_div",
                "reversals", "sigma_reading_arcsec", "target_reading", "target_sigma_arcsec", "target_rounds",
                "time", "observer", "stochastic_model"});
  gyro::DeterminationInput d;
  if (auto v = n.get("label")) d.label = v->string();
  if (auto v = n.get("time")) d.time = v->string();
  if (auto v = n.get("observer")) d.observer = v->string();
  if (auto v = n.get("stochastic_model")) d.stochastic_model = read_stochastic_choice(*v);
  d.mode = read_mode(n.require("mode"));
  if (auto v = n.get("method")) {
    const std::string name = v->string();
    try {
      if (name != "all") d.method = gyro::method_from_string(d.mode, name);
    } catch (Error& e) {
      v->fail(e.message());
    }
  }
  if (d.mode == gyro::Mode::Tracking)
    read_tracking_run(n, unit, d);
  else
    read_nontracking_run(n, inst, unit, d);
  read_zero_position(n, d);
  read_target(n, unit, d);
  return d;
}

std::vector<gyro::DeterminationInput> read_determinations(const Node& list,
                                                          const gyro::InstrumentSpec& inst,
                                                          AngleUnit unit) {
  std::vector<gyro::DeterminationInput> out;
  for (const auto& e : list.elements()) out.push_back(read_determination(e, inst, unit));
  return out;
}

gyro::ReduceOptions read_options(const Node& n) {
  n.allow_only({"zero_position_method", "estimate_damping", "zero_position_tolerance_div"});
  gyro::ReduceOptions o;
  if (auto v = n.get("zero_position_method")) {
    try {
      o.zero_position_method = gyro::reversal_method_from_string(v->string());
    } catch (Error& e) {
      v->fail(e.message());
    }
  }
  if (auto v = n.get("estimate_damping")) o.unified_fit.estimate_damping = v->boolean();
  if (auto v = n.get("zero_position_tolerance_div"))
    o.zero_position_tolerance_div = v->positive_number();
  return o;
}

gyro::PointInput read_point(const Node& n) {
  n.allow_only({"name", "latitude_deg", "longitude_deg", "x_m", "y_m", "eta_arcsec",
                "eta_sigma_arcsec", "height_m", "xi_arcsec", "xi_sigma_arcsec"});
  gyro::PointInput p;
  if (auto v = n.get("name")) p.name = v->string();
  if (auto v = n.get("latitude_deg")) {
    p.lat_rad = v->angle().rad();
    if (std::fabs(*p.lat_rad) > units::kPi / 2) v->fail("latitude must be within +-90 deg");
  }
  if (auto v = n.get("longitude_deg")) p.lon_rad = v->angle().rad();
  if (p.lat_rad.has_value() != p.lon_rad.has_value())
    n.fail("give both latitude_deg and longitude_deg");
  if (auto v = n.get("x_m")) {
    p.x_north_m = v->number();
    p.x_half_unit_m = geodesy::half_last_digit_m(v->string());
  }
  if (auto v = n.get("y_m")) {
    p.y_east_m = v->number();
    p.y_half_unit_m = geodesy::half_last_digit_m(v->string());
  }
  if (p.x_north_m.has_value() != p.y_east_m.has_value()) n.fail("give both x_m and y_m");
  if (!p.lat_rad && !p.x_north_m) n.fail("a point needs latitude_deg/longitude_deg or x_m/y_m");
  if (auto v = n.get("eta_arcsec"))
    p.eta_rad = Uncertain{v->number() * units::kArcsecond,
                          sigma_or(n, "eta_sigma_arcsec", 0.0) * units::kArcsecond};
  if (auto v = n.get("height_m")) p.height_m = v->number();
  if (auto v = n.get("xi_arcsec")) {
    const double xi = v->number() * units::kArcsecond;
    if (std::fabs(xi) > geodesy::kMaxDeflection_rad)
      v->fail("xi must be within +-0.01 rad (2062.6 arcsec); is it in arc-seconds?");
    p.xi_rad = Uncertain{xi, sigma_or(n, "xi_sigma_arcsec", 0.0) * units::kArcsecond};
  } else if (auto s = n.get("xi_sigma_arcsec")) {
    s->fail("xi_sigma_arcsec given without xi_arcsec");
  }
  return p;
}

// A booked zenith angle of a line's sight (in the book's angle unit, 10 to 170 deg).
double read_zenith_angle(const Node& v, AngleUnit unit) {
  const double z = v.angle(unit).rad();
  try {
    geodesy::check_zenith_distance(z);
  } catch (const Error& e) {
    v.fail(e.message());
  }
  return z;
}

geodesy::GridDefinition read_grid(const Node& n) {
  n.allow_only({"system", "zone", "ellipsoid", "hemisphere", "zone_prefix",
                "central_meridian_deg", "scale_factor", "false_easting_m", "false_northing_m"});
  geodesy::Ellipsoid e = geodesy::wgs84();
  if (auto v = n.get("ellipsoid")) {
    try {
      e = geodesy::ellipsoid_by_name(v->string());
    } catch (Error& err) {
      v->fail(err.message());
    }
  }
  const Node sys = n.require("system");
  const std::string s = sys.string();
  bool prefix = false;
  if (auto v = n.get("zone_prefix")) prefix = v->boolean();
  geodesy::GridDefinition g;
  auto zone = [&] { return n.require("zone").integer(); };
  try {
    if (s == "gk3" || s == "gauss-kruger-3")
      g = geodesy::gauss_kruger_3(zone(), e, prefix);
    else if (s == "gk6" || s == "gauss-kruger-6")
      g = geodesy::gauss_kruger_6(zone(), e, prefix);
    else if (s == "utm") {
      bool north = true;
      if (auto h = n.get("hemisphere")) {
        const std::string hs = h->string();
        if (hs == "north" || hs == "n") north = true;
        else if (hs == "south" || hs == "s") north = false;
        else h->fail("expected north or south");
      }
      g = geodesy::utm(zone(), north, e);
    } else if (s == "custom") {
      g.system = geodesy::ZoneSystem::Custom;
      g.ellipsoid = e;
      g.central_meridian_rad = n.require("central_meridian_deg").angle().rad();
      if (auto v = n.get("scale_factor")) g.scale_factor = v->positive_number();
      if (auto v = n.get("false_easting_m")) g.false_easting_m = v->number();
      if (auto v = n.get("false_northing_m")) g.false_northing_m = v->number();
    } else {
      sys.fail(fmt::format("unknown grid system \"{}\" (expected gk3, gk6, utm or custom)", s));
    }
    if (s != "custom")
      for (const char* k : {"central_meridian_deg", "scale_factor", "false_easting_m", "false_northing_m"})
        if (auto v = n.get(k)) v->fail("only for system custom");
    (void)geodesy::TransverseMercatorGrid(g);  // validates
  } catch (Error& err) {
    if (err.context().file.empty()) n.fail(err.message());
    throw;
  }
  return g;
}

// The model is a path (relative to the campaign file, or as given) or a name
// found where GeographicLib keeps its models; it is loaded by the caller.
gyro::GravityModelRef read_gravity_model_ref(const Node& n, const std::filesystem::path& campaign_path) {
  n.allow_only({"model", "max_degree", "eta_sigma_arcsec", "xi_sigma_arcsec"});
  gyro::GravityModelRef r;
  r.source = n.require("model").string();
  r.lookup = detail::model_lookup_path(campaign_path, r.source);
  if (auto v = n.get("max_degree")) {
    r.max_degree = v->integer();
    if (r.max_degree < 0) v->fail(fmt::format("max_degree must be >= 0 (leave it out for the model's full degree), not {}", r.max_degree));
  }
  if (auto v = n.get("eta_sigma_arcsec"))
    r.sigma_eta_rad = v->positive_number() * units::kArcsecond;
  if (auto v = n.get("xi_sigma_arcsec")) r.sigma_xi_rad = v->positive_number() * units::kArcsecond;
  return r;
}

// The record sheet: free text, shown in reports.
gyro::RecordSheet read_record(const Node& n) {
  n.allow_only({"observer", "booker", "computed_by", "checked_by", "date", "weather", "temperature", "remarks",
                "language"});
  gyro::RecordSheet r;
  for (const auto& [key, target] : detail::record_fields(r))
    if (auto v = n.get(key)) *target = v->string();
  if (auto v = n.get("language"); v && r.language != "en" && r.language != "zh")
    v->fail("language must be en (English) or zh (Chinese with the English terms)");
  return r;
}

// Overrides of the class limits (gyro/regulations.hpp).
gyro::Tolerances read_tolerances(const Node& t) {
  t.allow_only({"determination_difference_arcsec", "instrument_constant_difference_arcsec",
                "instrument_constant_means_arcsec", "orientation_difference_arcsec", "orientation_mean_sigma_arcsec",
                "zero_position_div", "zero_position_limit_div", "known_azimuth_coordinates_arcsec",
                "instrument_constant_max_arcsec", "line_coordinates_arcsec"});
  gyro::Tolerances r;
  for (const auto& f : detail::tolerance_fields(r))
    if (auto v = t.get(f.key)) *f.member = v->positive_number() * f.unit;
  return r;
}

// The station's latitude within the instrument's limit, and the instrument's constants resolved
// there (errors at fields "station.latitude_deg" and "instrument.…").
void check_constants(const gyro::ReduceInput& in) {
  try {
    gyro::check_latitude(in.latitude_rad, in.instrument.latitude_limit_rad);
  } catch (Error& e) {
    e.add_context("", std::nullopt, "station.latitude_deg");
    throw;
  }
  try {
    gyro::resolve_instrument(in.instrument, in.latitude_rad);
  } catch (Error& e) {
    e.add_context("", std::nullopt, "instrument");
    throw;
  }
}

}  // namespace

GyroReduceFile read_gyro_reduce_file(const std::filesystem::path& path) {
  const Node root = Node::load_file(path);
  root.allow_only({"angle_unit", "instrument", "station", "determinations", "options"});
  GyroReduceFile f;
  f.file = path.string();
  gyro::ReduceInput& in = f.input;
  in.file = f.file;
  in.angle_unit = read_angle_unit(root);
  const Node inst = root.require("instrument");
  in.instrument = read_instrument(inst);
  const Node st = root.require("station");
  st.allow_only({"name", "latitude_deg"});
  const Node lat = st.require("latitude_deg");
  in.latitude_rad = lat.angle().rad();
  if (std::fabs(in.latitude_rad) > units::kPi / 2) lat.fail("latitude must be within +-90 deg");
  if (auto o = root.get("options")) in.options = read_options(*o);
  const Node dets = root.require("determinations");
  in.determinations = read_determinations(dets, in.instrument, in.angle_unit);
  if (in.determinations.empty()) dets.fail("no determinations");
  for (const Node& d : dets.elements())
    if (auto v = d.get("stochastic_model"))
      v->fail("stochastic_model is a campaign option (gyro campaign); gyro reduce assumes "
              "independent readings, and gyro stochastic compares the models");
  f.lines = root.visited_lines();
  // The constants must resolve at this latitude: checked when the book is read, so that a book
  // that cannot be reduced fails at the line of its field (gyro stochastic reads it and does not
  // reduce it).
  SourceMap sources;
  sources.add_document(f.file, f.lines);
  located(sources, [&] { check_constants(in); });
  return f;
}

CampaignFile read_campaign_file(const std::filesystem::path& path) {
  return read_campaign_document(Node::load_file(path));
}

CampaignFile read_campaign_document(const Node& root) {
  const std::filesystem::path path = root.file();
  root.allow_only({"campaign", "angle_unit", "record", "instrument", "grid", "known_line", "instrument_constant",
                   "line", "tolerances", "options", "gravity_model", "stochastic_model"});
  CampaignFile f;
  f.file = root.file();
  gyro::CampaignInput& c = f.campaign;
  c.file = f.file;
  c.angle_unit = read_angle_unit(root);
  if (auto v = root.get("campaign")) c.name = v->string();
  if (auto r = root.get("record")) c.record = read_record(*r);
  if (auto v = root.get("stochastic_model")) c.stochastic_model = read_stochastic_choice(*v);
  c.instrument = read_instrument(root.require("instrument"));
  c.grid = read_grid(root.require("grid"));
  if (auto k = root.get("known_line")) {
    k->allow_only({"from", "to", "zenith_angle", "azimuth", "before", "after"});
    gyro::KnownLineInput kl;
    kl.from = read_point(k->require("from"));
    if (auto t = k->get("to")) kl.to = read_point(*t);
    if (auto z = k->get("zenith_angle")) kl.zenith_angle_rad = read_zenith_angle(*z, c.angle_unit);
    const Node az = k->require("azimuth");
    az.allow_only({"kind", "value", "sigma_arcsec"});
    const Node kind = az.require("kind");
    const std::string ks = kind.string();
    if (ks == "astronomic") kl.azimuth.kind = gyro::KnownAzimuth::Kind::Astronomic;
    else if (ks == "geodetic") kl.azimuth.kind = gyro::KnownAzimuth::Kind::Geodetic;
    else if (ks == "grid") kl.azimuth.kind = gyro::KnownAzimuth::Kind::Grid;
    else kind.fail(fmt::format("unknown azimuth kind \"{}\" (expected astronomic, geodetic or grid)", ks));
    kl.azimuth.value_rad = {read_circle_direction(az.require("value"), c.angle_unit).rad(),
                            sigma_or(az, "sigma_arcsec", 0.0) * units::kArcsecond};
    if (auto b = k->get("before")) kl.before = read_determinations(*b, c.instrument, c.angle_unit);
    if (auto a = k->get("after")) kl.after = read_determinations(*a, c.instrument, c.angle_unit);
    if (kl.before.empty() && kl.after.empty()) k->fail("give determinations before and/or after");
    for (const auto* list : {&kl.before, &kl.after})
      for (const auto& d : *list)
        if (!d.target_reading_rad && d.target_rounds.empty())
          k->fail("every known-line determination needs target_reading or target_rounds");
    c.known_line = std::move(kl);
  }
  if (auto e = root.get("instrument_constant")) {
    if (c.known_line) e->fail("give known_line or instrument_constant, not both");
    e->allow_only({"value", "sigma_arcsec"});
    c.instrument_constant_rad =
        Uncertain{e->require("value").angle(c.angle_unit).normalized_signed().rad(),
                  sigma_or(*e, "sigma_arcsec", 0.0) * units::kArcsecond};
  }
  if (!c.known_line && !c.instrument_constant_rad)
    root.fail("give known_line (calibration on a known line) or instrument_constant");
  const Node line = root.require("line");
  line.allow_only({"from", "to", "zenith_angle", "determinations"});
  c.line.from = read_point(line.require("from"));
  if (auto t = line.get("to")) c.line.to = read_point(*t);
  if (auto z = line.get("zenith_angle")) c.line.zenith_angle_rad = read_zenith_angle(*z, c.angle_unit);
  const Node dets = line.require("determinations");
  c.line.determinations = read_determinations(dets, c.instrument, c.angle_unit);
  if (c.line.determinations.empty()) dets.fail("no determinations");
  for (std::size_t i = 0; i < c.line.determinations.size(); ++i)
    if (!c.line.determinations[i].target_reading_rad && c.line.determinations[i].target_rounds.empty())
      dets.elements()[i].fail("every line determination needs target_reading or target_rounds");
  if (auto t = root.get("tolerances")) c.tolerances = read_tolerances(*t);
  if (auto o = root.get("options")) c.options = read_options(*o);
  if (auto g = root.get("gravity_model")) c.gravity_model = read_gravity_model_ref(*g, path);
  f.lines = root.visited_lines();
  return f;
}

}  // namespace meridian::io
