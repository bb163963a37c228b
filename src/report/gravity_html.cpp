#include "meridian/report/gravity_html.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "meridian/core/units.hpp"
#include "meridian/report/format.hpp"

namespace meridian::report {
namespace {

using fmtx::num;
using nlohmann::json;
constexpr int kMapWidth = 620;

// One mapped quantity: how to read it from a sample point, and how to show it.
struct Quantity {
  const char* id;
  const char* title;
  const char* axis;  // colour legend title
  double (*value)(const gravity::SamplePoint&);
  const char* scheme;
  bool diverging;  // centred on zero
};

const Quantity kQuantities[] = {
    {"xi", "North-south deflection xi", "xi (arcsec)",
     [](const gravity::SamplePoint& s) { return units::rad_to_arcsec(s.xi_rad); }, "blueorange",
     true},
    {"eta", "East-west deflection eta", "eta (arcsec)",
     [](const gravity::SamplePoint& s) { return units::rad_to_arcsec(s.eta_rad); }, "blueorange",
     true},
    {"geoid", "Geoid height N", "N (m)", [](const gravity::SamplePoint& s) { return s.geoid_m; },
     "viridis", false},
};

// Rounded for the page: 1e-7 deg is 1 cm, 1e-4" and 0.1 mm are below any
// model's accuracy; the CSV keeps every digit.
double rounded(double v, double unit) { return std::round(v / unit) * unit; }

// A height that keeps one degree of latitude about as long as one of
// longitude at the middle latitude, within limits that stay readable.
int map_height(const gravity::BoundingBox& b) {
  const double dlat = b.lat_max_rad - b.lat_min_rad;
  const double dlon =
      (b.lon_max_rad - b.lon_min_rad) * std::cos(0.5 * (b.lat_min_rad + b.lat_max_rad));
  if (!(dlat > 0) || !(dlon > 0)) return 320;
  return static_cast<int>(std::clamp(kMapWidth * dlat / dlon, 200.0, 620.0));
}

std::string drawn_caption(const gravity::PointsSummary& s) {
  const auto& sample = s.sample();
  if (sample.stride() == 1) return fmt::format("All {} points are drawn.", s.count());
  return fmt::format(
      "{} of {} points are drawn: one in every {}, from the first (a deterministic thinning to at "
      "most {} "
      "points; the statistics use every point).",
      sample.points().size(), s.count(), sample.stride(), sample.capacity());
}

Plot map_plot(const Quantity& q, const gravity::PointsSummary& s) {
  json values = json::array();
  for (const auto& p : s.sample().points())
    values.push_back({{"i", p.index + 1},
                      {"lat", rounded(units::rad_to_deg(p.lat_rad), 1e-7)},
                      {"lon", rounded(units::rad_to_deg(p.lon_rad), 1e-7)},
                      {"v", rounded(q.value(p), 1e-4)}});
  json scale = {{"scheme", q.scheme}};
  if (q.diverging) scale["domainMid"] = 0;
  const std::size_t n = s.sample().points().size();
  json spec = {
      {"width", kMapWidth},
      {"height", map_height(s.bounds())},
      {"data", {{"values", values}}},
      {"mark",
       {{"type", "circle"},
        {"size", n > 2000  ? 12
                 : n > 200 ? 30
                           : 60},
        {"opacity", 0.9}}},
      {"encoding",
       {{"x",
         {{"field", "lon"},
          {"type", "quantitative"},
          {"title", "longitude (deg, east +)"},
          {"scale", {{"zero", false}}}}},
        {"y",
         {{"field", "lat"},
          {"type", "quantitative"},
          {"title", "latitude (deg)"},
          {"scale", {{"zero", false}}}}},
        {"color", {{"field", "v"}, {"type", "quantitative"}, {"title", q.axis}, {"scale", scale}}},
        {"tooltip", json::array({{{"field", "i"}, {"title", "point"}},
                                 {{"field", "lat"}, {"title", "latitude (deg)"}},
                                 {{"field", "lon"}, {"title", "longitude (deg)"}},
                                 {{"field", "v"}, {"title", q.axis}}})}}}};
  return {q.title, spec, drawn_caption(s) + (q.diverging ? " Colour scale centred on zero." : "")};
}

std::string evaluation_text(const gravity::PointsOptions& o) {
  if (!o.along_track()) return "every point with the full model";
  return fmt::format(
      "one survey line: the model at a subset of the points, linear interpolation in along-track "
      "distance "
      "elsewhere, interpolation error checked at every interval's midpoint to at most {}\" in xi "
      "and eta and {} m "
      "in N, in chunks of {} points",
      num(units::rad_to_arcsec(o.track_tolerance_rad), 6), o.track_tolerance_geoid_m,
      gravity::points_chunk_size(o));
}

Section summary_section(const gravity::PointsSummary& s) {
  Section sec{"summary", "Summary", {}, 2};
  sec.blocks.push_back(Highlight{"Points evaluated", std::to_string(s.count()), ""});
  if (s.count() == 0) {
    sec.blocks.push_back(
        Paragraph{"The input had no points: there are no statistics and no maps."});
    return sec;
  }
  Table t;
  t.title = "Statistics over every point";
  t.columns = {"quantity", "unit", "minimum", "maximum", "mean", "RMS", "standard deviation"};
  t.numeric = {false, false, true, true, true, true, true};
  auto row = [&](const char* name, const char* unit, const gravity::RunningStatistics& r,
                 double scale, int dec) {
    t.rows.push_back({name, unit, num(r.min() * scale, dec), num(r.max() * scale, dec),
                      num(r.mean() * scale, dec), num(r.rms() * scale, dec),
                      num(r.std_dev() * scale, dec)});
  };
  const double to_arcsec = 1.0 / units::kArcsecond;
  row("xi (north-south deflection)", "arcsec", s.xi_rad(), to_arcsec, 4);
  row("eta (east-west deflection)", "arcsec", s.eta_rad(), to_arcsec, 4);
  row("N (geoid height)", "m", s.geoid_m(), 1.0, 4);
  t.note =
      "RMS = sqrt(sum x^2 / n); standard deviation = sqrt(sum (x - mean)^2 / (n - 1)), n/a for one "
      "point.";
  sec.blocks.push_back(t);
  const gravity::BoundingBox& b = s.bounds();
  Table e;
  e.title = "Extent of the points";
  e.columns = {"coordinate", "minimum", "maximum"};
  e.numeric = {false, true, true};
  e.rows = {{"latitude (deg)", num(units::rad_to_deg(b.lat_min_rad), 7),
             num(units::rad_to_deg(b.lat_max_rad), 7)},
            {"longitude (deg, as given)", num(units::rad_to_deg(b.lon_min_rad), 7),
             num(units::rad_to_deg(b.lon_max_rad), 7)},
            {"ellipsoidal height (m)", num(b.height_min_m, 3), num(b.height_max_m, 3)}};
  sec.blocks.push_back(e);
  return sec;
}

Section definitions_section(const gravity::PointsOptions& o) {
  Section sec{"definitions", "Definitions and signs", {}, 2};
  sec.blocks.push_back(Notes{
      "",
      {"xi and eta are the components of the deflection of the vertical, astronomic minus "
       "geodetic: "
       "xi = Phi - phi (north-south), eta = (Lambda - lambda) cos phi (east-west). xi > 0 when the "
       "plumb line "
       "points north of the ellipsoid normal (astronomic latitude greater), eta > 0 when it points "
       "east.",
       "They are computed as GeographicLib's SphericalAnomaly defines them: xi = -(1/gamma)(1/r) "
       "dT/dpsi, "
       "eta = -(1/gamma)(1/(r cos psi)) dT/dlambda, with T the disturbing potential of the model, "
       "psi the "
       "geocentric latitude and gamma the normal gravity at the point (its height included).",
       "N is the geoid height on the ellipsoid by Bruns' formula, N = T(phi, lambda, "
       "0)/gamma0(phi), plus the "
       "model's zeta-to-N correction when it has one; the point's height does not enter.",
       "Evaluation: " + evaluation_text(o) + ".",
       "See docs/gravity-field.md for the formulas and their validation against GeographicLib."},
      false});
  return sec;
}

}  // namespace

Document gravity_points_document(const gravity::PointsResult& result) {
  const std::string& input = result.input;
  const gravity::ModelInfo& model = result.model;
  const gravity::PointsSummary& summary = result.summary;
  Document doc;
  doc.title = "Deflection of the vertical and geoid heights at points";
  doc.subtitle = input;
  doc.footer = report_generator();
  doc.header = {{"input", input},
                {"model", model.name},
                {"model file", model.source_file},
                {"degree evaluated", model.max_degree == model.file_max_degree
                                         ? std::to_string(model.max_degree)
                                         : fmt::format("{} (the file has {})", model.max_degree,
                                                       model.file_max_degree)},
                {"model GM", fmt::format("{} m^3/s^2", model.gm_m3_s2)},
                {"model reference radius", fmt::format("{} m", model.radius_m)},
                {"tide system", model.tide_system.empty() ? "not stated by the file" : model.tide_system},
                {"normalisation", gravity::normalization_text(model)},
                {"evaluation", evaluation_text(result.options)},
                {"points", std::to_string(summary.count())}};
  if (const auto warnings = gravity::model_warnings(model); !warnings.empty()) {
    Section w{"warnings", "Warnings", {}, 2};
    w.blocks.push_back(Notes{"", warnings, true});
    doc.sections.push_back(w);
  }
  doc.sections.push_back(summary_section(summary));
  if (summary.count() > 0) {
    Section maps{"maps", "Maps", {}, 2};
    for (const Quantity& q : kQuantities) maps.blocks.push_back(map_plot(q, summary));
    doc.sections.push_back(maps);
  }
  doc.sections.push_back(definitions_section(result.options));
  return doc;
}

}  // namespace meridian::report
