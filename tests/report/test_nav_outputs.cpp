// The navigation writers (report/nav_outputs.hpp, report/nav_html.hpp) on hand-made results:
// JSON keys and nulls, CSV headers, rows and exact round trip of numbers, RFC 7946 GeoJSON in
// [longitude, latitude] order, the errors, the text and the report document.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/geodesy/grid.hpp"
#include "meridian/report/html.hpp"
#include "meridian/report/nav_html.hpp"
#include "meridian/report/nav_outputs.hpp"

using namespace meridian;
using namespace meridian::report;
using nlohmann::json;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

// A track of n epochs every 5 s on a line north-east, with numbers that need 17 digits.
std::vector<nav::TrackPoint> make_track(std::size_t n, double offset_m, bool bias_sigma) {
  std::vector<nav::TrackPoint> t;
  for (std::size_t k = 0; k < n; ++k) {
    nav::TrackPoint p;
    const double kd = static_cast<double>(k);
    p.time_s = 36000.0 + 5.0 * kd + 0.1;
    p.x_north_m = 4100000.0 + 2.5 * kd + offset_m + 1.0 / 3.0;
    p.y_east_m = 500000.0 + 4.330127018922193 * kd - offset_m + 2.0 / 7.0;
    p.covariance << 25.0 + 0.1 * kd, 3.0 + 1.0 / 3.0, 3.0 + 1.0 / 3.0, 16.0 + 0.2 * kd;
    p.bias_north_m_s = -0.25 + 1e-3 * kd / 3.0;
    p.bias_east_m_s = -0.433 - 1e-3 * kd / 7.0;
    p.sigma_bias_north_m_s = bias_sigma ? 0.05 / (1.0 + kd) : 0.0;
    p.sigma_bias_east_m_s = bias_sigma ? 0.06 / (1.0 + kd) : 0.0;
    p.flags = k % 3 == 0 ? nav::kUsedLop : (k % 3 == 1 ? (nav::kUsedLop | nav::kRejectedLop) : 0u);
    t.push_back(p);
  }
  return t;
}

nav::ErrorStatistics make_errors(double rms, double nees) {
  nav::ErrorStatistics e;
  e.epochs = 12;
  e.rms_m = rms;
  e.max_error_m = 2.5 * rms;
  e.per_minute_rms_m = {rms * 0.5, kNaN, rms * 1.5};
  e.mean_nees = nees;
  return e;
}

// Every method but fix-closure, with truth; dead reckoning's NEES not finite.
nav::Result make_result(std::size_t epochs = 12, bool truth = true) {
  nav::Result r;
  r.epochs = epochs;
  r.lops_used = 30;
  r.fixes_used = 1;
  double offset = 0.0;
  for (nav::Method m : nav::kAllMethods) {
    if (m == nav::Method::FixClosure) continue;
    nav::MethodResult mr;
    mr.method = m;
    const bool sigma = m == nav::Method::Ekf || m == nav::Method::Rts;
    mr.track = make_track(epochs, offset, sigma);
    if (m == nav::Method::DeadReckoning || m == nav::Method::SequentialNoBias)
      for (auto& p : mr.track) p.bias_north_m_s = p.bias_east_m_s = 0.0;
    offset += 3.0;
    if (truth)
      mr.errors = make_errors(10.0 + offset,
                              m == nav::Method::DeadReckoning ? std::numeric_limits<double>::infinity()
                                                              : 1.5 + offset / 10.0);
    if (m == nav::Method::SequentialBiasI) {
      mr.parameters.push_back({0, "Syledis", "scale", 1.5e-5, 2.0e-6});
      mr.parameters.push_back({0, "Syledis", "offset_m", 12.25, 1.5});
    }
    r.methods.push_back(mr);
  }
  nav::RejectedObservation a;
  a.kind = nav::RejectedObservation::Kind::Lop;
  a.index = 7;
  a.method = nav::Method::SequentialBiasI;
  a.time_s = 36015.1;
  a.misclosure_m = 153.21;
  a.statistic = 0.0;
  a.reason = "misclosure 153.2 m > 100 m, \"lane slip\"?";
  a.source = "lops.csv:9";
  r.rejected.push_back(a);
  nav::RejectedObservation b = a;
  b.method = nav::Method::Ekf;
  b.statistic = 4.1;
  b.reason = "w = 4.1 > 3.29\nsecond line";
  r.rejected.push_back(b);
  nav::RejectedObservation f;
  f.kind = nav::RejectedObservation::Kind::Fix;
  f.index = 0;
  f.method = nav::Method::Rts;
  f.time_s = 36040.1;
  f.misclosure_m = 250.0;
  f.statistic = 6.5;
  f.reason = "fix 250 m from the forward solution > 200 m";
  r.rejected.push_back(f);
  r.skipped.push_back({nav::RejectedObservation::Kind::Lop, 29, 99999.0, "outside the DR span", "lops.csv:31"});
  r.notes = {"initial position sigma 100 m (default)"};
  r.warnings = {"no LOP between 36020 s and 36040 s"};
  return r;
}

// A transverse Mercator on WGS 84 (the result's projection as data) whose central meridian is
// lon0 and whose point (x0, y0) lies at latitude lat0 on it.
geodesy::GridDefinition local_projection(double lat0_deg, double lon0_deg, double x0_m, double y0_m) {
  geodesy::GridDefinition g;
  g.system = geodesy::ZoneSystem::Custom;
  g.central_meridian_rad = lon0_deg * units::kDegree;
  g.scale_factor = 1.0;
  g.false_easting_m = y0_m;
  g.false_northing_m = 0.0;
  g.false_northing_m = x0_m - geodesy::TransverseMercatorGrid(g).forward(lat0_deg * units::kDegree, g.central_meridian_rad).x_north_m;
  return g;
}

const geodesy::GridDefinition kWestCoast = local_projection(37.5, -122.25, 4100000.0, 500000.0);

// {latitude, longitude} (rad) of a plane point in kWestCoast.
std::array<double, 2> west_coast(double x_north_m, double y_east_m) {
  const geodesy::GeographicPoint q = geodesy::TransverseMercatorGrid(kWestCoast).reverse(x_north_m, y_east_m);
  return {q.lat_rad, q.lon_rad};
}

// The result with the projection.
nav::Result projected(nav::Result r, const geodesy::GridDefinition& g) {
  r.projection = g;
  return r;
}

std::vector<std::string> lines_of(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::vector<std::string> split(const std::string& s, char d = ',') {
  std::vector<std::string> out;
  std::string field;
  for (char c : s) {
    if (c == d) {
      out.push_back(field);
      field.clear();
    } else {
      field += c;
    }
  }
  out.push_back(field);
  return out;
}

double number(const std::string& s) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  EXPECT_EQ(*end, '\0') << s;
  return v;
}

// RFC 4180 record of one line: fields, quotes removed and doubled quotes undone.
std::vector<std::string> parse_rfc4180(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.push_back(field);
      field.clear();
    } else {
      field += c;
    }
  }
  EXPECT_FALSE(quoted) << line;
  out.push_back(field);
  return out;
}

const Section* find_section(const Document& d, const std::string& id) {
  for (const auto& s : d.sections)
    if (s.id == id) return &s;
  return nullptr;
}

template <class T>
std::vector<const T*> blocks(const Section& s) {
  std::vector<const T*> out;
  for (const auto& b : s.blocks)
    if (const auto* p = std::get_if<T>(&b)) out.push_back(p);
  return out;
}

std::size_t plot_count(const Document& d) {
  std::size_t n = 0;
  for (const auto& s : d.sections) n += blocks<Plot>(s).size();
  return n;
}

}  // namespace

// ---- JSON ----------------------------------------------------------------------------------

TEST(NavJson, HasEveryMethodWithItsStatisticsAndNullForNaN) {
  const nav::Result r = make_result();
  const json j = nav_to_json(r);
  EXPECT_EQ(j["epochs"], 12);
  EXPECT_EQ(j["lops_used"], 30);
  EXPECT_EQ(j["fixes_used"], 1);
  ASSERT_TRUE(j["methods"].is_object());
  EXPECT_EQ(j["methods"].size(), r.methods.size());
  EXPECT_EQ(j["method_order"].size(), r.methods.size());
  for (const char* name : {"dead-reckoning", "sequential-no-bias", "sequential-bias-I",
                           "sequential-bias-II", "backward", "ekf", "rts"}) {
    ASSERT_TRUE(j["methods"].contains(name)) << name;
    const json& m = j["methods"][name];
    for (const char* key : {"epochs", "rms_m", "max_error_m", "per_minute_rms_m", "mean_nees",
                            "error_epochs", "estimates_bias", "bias_north_m_s", "bias_east_m_s",
                            "sigma_bias_north_m_s", "sigma_bias_east_m_s", "final_position",
                            "parameters", "rejected_lops", "flagged_fixes"})
      EXPECT_TRUE(m.contains(key)) << name << " " << key;
    ASSERT_EQ(m["per_minute_rms_m"].size(), 3u);
    EXPECT_TRUE(m["per_minute_rms_m"][0].is_number());
    EXPECT_TRUE(m["per_minute_rms_m"][1].is_null()) << "a bin without truth";
    EXPECT_EQ(m["epochs"], 12);
  }
  EXPECT_FALSE(j["methods"].contains("fix-closure"));
  const nav::MethodResult& bias1 = *r.find(nav::Method::SequentialBiasI);
  const json& b1 = j["methods"]["sequential-bias-I"];
  EXPECT_DOUBLE_EQ(b1["rms_m"].get<double>(), bias1.errors->rms_m);
  EXPECT_DOUBLE_EQ(b1["max_error_m"].get<double>(), bias1.errors->max_error_m);
  EXPECT_DOUBLE_EQ(b1["mean_nees"].get<double>(), bias1.errors->mean_nees);
  EXPECT_DOUBLE_EQ(b1["per_minute_rms_m"][2].get<double>(), bias1.errors->per_minute_rms_m[2]);
  EXPECT_EQ(b1["bias_north_m_s"].get<double>(), bias1.track.back().bias_north_m_s);
  EXPECT_EQ(b1["bias_east_m_s"].get<double>(), bias1.track.back().bias_east_m_s);
  EXPECT_TRUE(b1["sigma_bias_north_m_s"].is_null()) << "method I states no σ";
  EXPECT_TRUE(b1["sigma_bias_east_m_s"].is_null());
  EXPECT_TRUE(b1["estimates_bias"].get<bool>());
  EXPECT_EQ(b1["rejected_lops"], 1);
  EXPECT_EQ(b1["flagged_fixes"], 0);
  ASSERT_EQ(b1["parameters"].size(), 2u);
  EXPECT_EQ(b1["parameters"][0]["chain"], 0);
  EXPECT_EQ(b1["parameters"][0]["chain_name"], "Syledis");
  EXPECT_EQ(b1["parameters"][0]["name"], "scale");
  EXPECT_DOUBLE_EQ(b1["parameters"][0]["value"].get<double>(), 1.5e-5);
  EXPECT_DOUBLE_EQ(b1["parameters"][0]["sigma"].get<double>(), 2.0e-6);
  EXPECT_EQ(b1["parameters"][1]["name"], "offset_m");
  const json& fp = b1["final_position"];
  EXPECT_EQ(fp["x_north_m"].get<double>(), bias1.track.back().x_north_m);
  EXPECT_EQ(fp["y_east_m"].get<double>(), bias1.track.back().y_east_m);
  EXPECT_DOUBLE_EQ(fp["sigma_x_m"].get<double>(), std::sqrt(bias1.track.back().covariance(0, 0)));
  EXPECT_DOUBLE_EQ(fp["cov_xy_m2"].get<double>(), 3.0 + 1.0 / 3.0);

  const json& ekf = j["methods"]["ekf"];
  EXPECT_DOUBLE_EQ(ekf["sigma_bias_north_m_s"].get<double>(), 0.05 / 12.0);
  EXPECT_DOUBLE_EQ(ekf["sigma_bias_east_m_s"].get<double>(), 0.06 / 12.0);
  EXPECT_EQ(ekf["rejected_lops"], 1);
  EXPECT_EQ(j["methods"]["rts"]["flagged_fixes"], 1);
  const json& dr = j["methods"]["dead-reckoning"];
  EXPECT_TRUE(dr["mean_nees"].is_null()) << "an infinite NEES is null";
  EXPECT_FALSE(dr["estimates_bias"].get<bool>());
  EXPECT_EQ(dr["bias_north_m_s"].get<double>(), 0.0);
  EXPECT_TRUE(dr["sigma_bias_north_m_s"].is_null());

  ASSERT_EQ(j["rejected"].size(), 3u);
  const json& rej = j["rejected"][0];
  EXPECT_EQ(rej["kind"], "lop");
  EXPECT_EQ(rej["index"], 7);
  EXPECT_EQ(rej["method"], "sequential-bias-I");
  EXPECT_DOUBLE_EQ(rej["time_s"].get<double>(), 36015.1);
  EXPECT_DOUBLE_EQ(rej["misclosure_m"].get<double>(), 153.21);
  EXPECT_DOUBLE_EQ(rej["statistic"].get<double>(), 0.0);
  EXPECT_EQ(rej["reason"], r.rejected[0].reason);
  EXPECT_EQ(j["rejected"][2]["kind"], "fix");
  ASSERT_EQ(j["skipped"].size(), 1u);
  EXPECT_EQ(j["skipped"][0]["kind"], "lop");
  EXPECT_EQ(j["skipped"][0]["index"], 29);
  EXPECT_EQ(j["skipped"][0]["reason"], "outside the DR span");
  EXPECT_EQ(j["skipped"][0]["source"], "lops.csv:31");
  EXPECT_EQ(j["notes"], json(r.notes));
  EXPECT_EQ(j["warnings"], json(r.warnings));
  // The text parses back as the same document, with no NaN or Infinity token.
  const std::string text = j.dump();
  EXPECT_EQ(text.find("NaN"), std::string::npos);
  EXPECT_EQ(text.find("nan"), std::string::npos);
  EXPECT_EQ(text.find("Infinity"), std::string::npos);
  EXPECT_EQ(json::parse(text), j);
}

TEST(NavJson, WithoutTruthTheErrorStatisticsAreNull) {
  nav::Result r = make_result(4, false);
  r.methods.push_back(nav::MethodResult{nav::Method::FixClosure, {}, {}, std::nullopt});
  const json j = nav_to_json(r);
  for (const auto& [name, m] : j["methods"].items()) {
    EXPECT_TRUE(m["rms_m"].is_null()) << name;
    EXPECT_TRUE(m["max_error_m"].is_null()) << name;
    EXPECT_TRUE(m["mean_nees"].is_null()) << name;
    EXPECT_TRUE(m["error_epochs"].is_null()) << name;
    EXPECT_TRUE(m["per_minute_rms_m"].is_array()) << name;
    EXPECT_TRUE(m["per_minute_rms_m"].empty()) << name;
  }
  // A method without epochs has no final values.
  const json& fc = j["methods"]["fix-closure"];
  EXPECT_EQ(fc["epochs"], 0);
  EXPECT_TRUE(fc["bias_north_m_s"].is_null());
  EXPECT_TRUE(fc["final_position"].is_null());
  EXPECT_TRUE(fc["sigma_horizontal_mean_m"].is_null());
  EXPECT_NEAR(j["methods"]["ekf"]["sigma_horizontal_max_m"].get<double>(), std::sqrt(41.9), 1e-12);
  EXPECT_EQ(j["methods"]["rts"]["observations_of"], "ekf");
  EXPECT_EQ(j["methods"]["backward"]["observations_of"], "sequential-bias-I");
  EXPECT_TRUE(j["methods"]["ekf"]["observations_of"].is_null());
}

// ---- track CSV -----------------------------------------------------------------------------

TEST(NavTrackCsv, HeaderRowsAndExactRoundTripWithoutProjection) {
  const nav::Result r = make_result();
  const std::string csv = nav_track_csv(r, nav::Method::Ekf);
  const auto lines = lines_of(csv);
  ASSERT_GE(lines.size(), 3u);
  EXPECT_EQ(lines[0].rfind("# ", 0), 0u);
  EXPECT_NE(lines[0].find("ekf"), std::string::npos) << "the first comment names the method";
  std::size_t h = 0;
  while (h < lines.size() && lines[h].rfind("#", 0) == 0) ++h;
  ASSERT_LT(h, lines.size());
  EXPECT_EQ(lines[h],
            "time_s,x_m,y_m,sigma_x_m,sigma_y_m,cov_xy_m2,bias_north_m_s,bias_east_m_s,"
            "sigma_bias_north_m_s,sigma_bias_east_m_s,flags");
  const auto& track = r.find(nav::Method::Ekf)->track;
  ASSERT_EQ(lines.size(), h + 1 + track.size());
  for (std::size_t k = 0; k < track.size(); ++k) {
    const auto f = split(lines[h + 1 + k]);
    ASSERT_EQ(f.size(), 11u) << lines[h + 1 + k];
    const nav::TrackPoint& p = track[k];
    EXPECT_EQ(number(f[0]), p.time_s);
    EXPECT_EQ(number(f[1]), p.x_north_m);
    EXPECT_EQ(number(f[2]), p.y_east_m);
    EXPECT_EQ(number(f[3]), p.sigma_x_m());
    EXPECT_EQ(number(f[4]), p.sigma_y_m());
    EXPECT_EQ(number(f[5]), p.covariance(0, 1));
    EXPECT_EQ(number(f[6]), p.bias_north_m_s);
    EXPECT_EQ(number(f[7]), p.bias_east_m_s);
    EXPECT_EQ(number(f[8]), p.sigma_bias_north_m_s);
    EXPECT_EQ(number(f[9]), p.sigma_bias_east_m_s);
    EXPECT_EQ(f[10], std::to_string(p.flags));
  }
}

TEST(NavTrackCsv, WithAProjectionHasLatitudeAndLongitude) {
  const nav::Result r = projected(make_result(), kWestCoast);
  const std::string csv = nav_track_csv(r, nav::Method::Rts);
  const auto lines = lines_of(csv);
  std::size_t h = 0;
  while (lines[h].rfind("#", 0) == 0) ++h;
  EXPECT_EQ(lines[h],
            "time_s,x_m,y_m,lat_deg,lon_deg,sigma_x_m,sigma_y_m,cov_xy_m2,bias_north_m_s,"
            "bias_east_m_s,sigma_bias_north_m_s,sigma_bias_east_m_s,flags");
  const auto& track = r.find(nav::Method::Rts)->track;
  ASSERT_EQ(lines.size(), h + 1 + track.size());
  for (std::size_t k = 0; k < track.size(); ++k) {
    const auto f = split(lines[h + 1 + k]);
    ASSERT_EQ(f.size(), 13u);
    const auto ll = geodesy::TransverseMercatorGrid(kWestCoast).reverse(track[k].x_north_m, track[k].y_east_m);
    EXPECT_EQ(number(f[3]), units::rad_to_deg(ll.lat_rad));
    EXPECT_EQ(number(f[4]), units::rad_to_deg(ll.lon_rad));
    EXPECT_NEAR(number(f[3]), 37.5, 0.01);
    EXPECT_NEAR(number(f[4]), -122.25, 0.01);
    EXPECT_EQ(number(f[1]), track[k].x_north_m);
  }
}

TEST(NavTrackCsv, AMethodNotInTheResultIsAnInputErrorNamingIt) {
  const nav::Result r = make_result();
  try {
    (void)nav_track_csv(r, nav::Method::FixClosure);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("fix-closure"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("rts"), std::string::npos) << "names what the result holds";
  }
}

TEST(NavTrackCsv, ANonGeographicProjectionIsAnInputError) {
  // the track 10 000 km east of the central meridian: no geographic position
  geodesy::GridDefinition far = kWestCoast;
  far.false_easting_m = -1e7;
  const nav::Result r = projected(make_result(), far);
  EXPECT_THROW((void)nav_track_csv(r, nav::Method::Rts), InputError);
  EXPECT_THROW((void)nav_track_geojson(r, {nav::Method::Rts}), InputError);
}

// ---- GeoJSON -------------------------------------------------------------------------------

TEST(NavGeoJson, IsAFeatureCollectionInLongitudeLatitudeOrder) {
  const nav::Result r = projected(make_result(), kWestCoast);
  const std::vector<nav::Method> methods{nav::Method::SequentialBiasI, nav::Method::Rts};
  const std::string text = nav_track_geojson(r, methods);
  const json g = json::parse(text);
  EXPECT_EQ(g["type"], "FeatureCollection");
  EXPECT_FALSE(g.contains("crs")) << "RFC 7946 has no crs member";
  ASSERT_TRUE(g["features"].is_array());
  std::size_t tracks = 0, rejected = 0;
  for (const json& f : g["features"]) {
    EXPECT_EQ(f["type"], "Feature");
    ASSERT_TRUE(f["properties"].is_object());
    const std::string method = f["properties"]["method"];
    const nav::MethodResult& m = *r.find(nav::method_from_string(method));
    if (f["properties"]["feature"] == "track") {
      ++tracks;
      EXPECT_EQ(method, nav::to_string(methods[tracks - 1])) << "in the order asked";
      EXPECT_EQ(f["geometry"]["type"], "LineString");
      const json& c = f["geometry"]["coordinates"];
      ASSERT_EQ(c.size(), m.track.size());
      for (std::size_t k = 0; k < m.track.size(); ++k) {
        ASSERT_EQ(c[k].size(), 2u);
        const auto ll = west_coast(m.track[k].x_north_m, m.track[k].y_east_m);
        EXPECT_NEAR(c[k][0].get<double>(), units::rad_to_deg(ll[1]), 6e-10) << "longitude first";
        EXPECT_NEAR(c[k][1].get<double>(), units::rad_to_deg(ll[0]), 6e-10) << "latitude second";
      }
      EXPECT_DOUBLE_EQ(f["properties"]["rms_m"].get<double>(), m.errors->rms_m);
      EXPECT_EQ(f["properties"]["epochs"], m.track.size());
    } else {
      ++rejected;
      EXPECT_EQ(f["properties"]["feature"], "rejected");
      EXPECT_EQ(f["geometry"]["type"], "Point");
      const bool lop = f["properties"]["kind"] == "lop";
      EXPECT_EQ(f["properties"]["index"], lop ? 7 : 0);
      EXPECT_EQ(method, lop ? "sequential-bias-I" : "rts");
      EXPECT_TRUE(f["properties"].contains("reason"));
      EXPECT_TRUE(f["properties"].contains("misclosure_m"));
      // At the method's position at the epoch nearest the observation (LOP 36015.1 s: epoch
      // 3; fix 36040.1 s: epoch 8).
      const std::size_t k = lop ? 3 : 8;
      const auto ll = west_coast(m.track[k].x_north_m, m.track[k].y_east_m);
      EXPECT_NEAR(f["geometry"]["coordinates"][0].get<double>(), units::rad_to_deg(ll[1]), 6e-10);
      EXPECT_NEAR(f["geometry"]["coordinates"][1].get<double>(), units::rad_to_deg(ll[0]), 6e-10);
    }
  }
  EXPECT_EQ(tracks, 2u);
  EXPECT_EQ(rejected, 2u) << "only the rejections of the methods written (bias-I's LOP, rts's fix)";
  // Coordinates with 7 or more decimals (1e-9 degree kept).
  const std::regex coordinate(R"(\[(-?\d+\.\d+),(-?\d+\.\d+)\])");
  std::size_t checked = 0;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), coordinate); it != std::sregex_iterator();
       ++it, ++checked) {
    for (int g2 : {1, 2}) {
      const std::string v = (*it)[g2].str();
      EXPECT_GE(v.size() - v.find('.') - 1, 7u) << v;
    }
  }
  EXPECT_GT(checked, 20u);
}

TEST(NavGeoJson, EveryMethodWhenNoneIsNamedAndWithoutTruthNoRms) {
  const nav::Result r = projected(make_result(3, false), kWestCoast);
  const json g = json::parse(nav_track_geojson(r, {}));
  std::size_t tracks = 0;
  for (const json& f : g["features"])
    if (f["properties"]["feature"] == "track") {
      ++tracks;
      EXPECT_FALSE(f["properties"].contains("rms_m"));
    }
  EXPECT_EQ(tracks, r.methods.size());
}

TEST(NavGeoJson, NeedsAProjection) {
  const nav::Result r = make_result();
  try {
    (void)nav_track_geojson(r, {nav::Method::Rts});
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("projection"), std::string::npos) << what;
    EXPECT_NE(what.find("geographic"), std::string::npos) << what;
  }
  EXPECT_THROW((void)nav_track_geojson(projected(r, kWestCoast), {nav::Method::FixClosure}), InputError);
}

TEST(NavGeoJson, ATrackAcrossTheAntimeridianIsCutThere) {
  nav::Result r;
  nav::MethodResult m;
  m.method = nav::Method::Rts;
  for (int k = 0; k < 5; ++k) {
    nav::TrackPoint p;
    p.time_s = k;
    p.x_north_m = 100.0 * k;
    p.y_east_m = 2000.0 * k;  // eastwards across 180°
    m.track.push_back(p);
  }
  r.methods.push_back(m);
  r.epochs = 5;
  r.projection = local_projection(-16.5, 179.95, 0.0, 0.0);
  const json g = json::parse(nav_track_geojson(r, {}));
  const json& geom = g["features"][0]["geometry"];
  ASSERT_EQ(geom["type"], "MultiLineString");
  ASSERT_EQ(geom["coordinates"].size(), 2u);
  const json& west = geom["coordinates"][0];
  const json& east = geom["coordinates"][1];
  EXPECT_EQ(west.back()[0].get<double>(), 180.0);
  EXPECT_EQ(east.front()[0].get<double>(), -180.0);
  EXPECT_EQ(west.back()[1], east.front()[1]) << "the same latitude on both sides";
  for (const json& part : geom["coordinates"]) {
    EXPECT_GE(part.size(), 2u);
    for (const json& c : part) {
      EXPECT_LE(std::fabs(c[0].get<double>()), 180.0);
      EXPECT_LT(c[1].get<double>(), -16.0);
    }
  }
  EXPECT_EQ(west.size() + east.size(), 5u + 2u);
}

TEST(NavGeoJson, AOneEpochTrackIsAPoint) {
  nav::Result r;
  nav::MethodResult m;
  m.method = nav::Method::Ekf;
  m.track.push_back(nav::TrackPoint{});
  r.methods.push_back(m);
  r.projection = kWestCoast;
  const json g = json::parse(nav_track_geojson(r, {}));
  EXPECT_EQ(g["features"][0]["geometry"]["type"], "Point");
  EXPECT_NEAR(g["features"][0]["geometry"]["coordinates"][0].get<double>(),
              units::rad_to_deg(geodesy::TransverseMercatorGrid(kWestCoast).reverse(0, 0).lon_rad), 1e-9);
}

// ---- rejected CSV --------------------------------------------------------------------------

TEST(NavRejectedCsv, HeaderRowsAndQuotedReasons) {
  const nav::Result r = make_result();
  const auto lines = lines_of(nav_rejected_csv(r));
  ASSERT_EQ(lines.size(), 1u + r.rejected.size()) << "one line per row (the line break of a "
                                                     "reason written as a space)";
  EXPECT_EQ(lines[0], "kind,index,method,time_s,misclosure_m,statistic,reason,source");
  for (std::size_t i = 0; i < r.rejected.size(); ++i) {
    const auto f = parse_rfc4180(lines[i + 1]);
    ASSERT_EQ(f.size(), 8u) << lines[i + 1];
    const auto& o = r.rejected[i];
    EXPECT_EQ(f[0], o.kind == nav::RejectedObservation::Kind::Lop ? "lop" : "fix");
    EXPECT_EQ(f[1], std::to_string(o.index));
    EXPECT_EQ(f[2], nav::to_string(o.method));
    EXPECT_EQ(number(f[3]), o.time_s);
    EXPECT_EQ(number(f[4]), o.misclosure_m);
    EXPECT_EQ(number(f[5]), o.statistic);
    std::string reason = o.reason;
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    EXPECT_EQ(f[6], reason);
    EXPECT_EQ(f[7], o.source);
  }
  EXPECT_NE(lines[1].find("\"misclosure 153.2 m > 100 m, \"\"lane slip\"\"?\""), std::string::npos)
      << lines[1];
  EXPECT_EQ(lines_of(nav_rejected_csv(nav::Result{})).size(), 1u) << "the header alone";
}

// ---- text ----------------------------------------------------------------------------------

TEST(NavText, NamesEveryMethodWithItsFigures) {
  const nav::Result r = make_result();
  const std::string t = nav_summary_text(r);
  for (const auto& m : r.methods) EXPECT_NE(t.find(nav::to_string(m.method)), std::string::npos) << t;
  EXPECT_NE(t.find("RMS"), std::string::npos);
  EXPECT_NE(t.find("mean NEES"), std::string::npos);
  EXPECT_NE(t.find("19.00"), std::string::npos) << "bias-I RMS 10 + 9 m";
  EXPECT_NE(t.find("not estimated"), std::string::npos) << "dead reckoning has no bias";
  // The EKF's final bias with σ; method I's without.
  EXPECT_NE(t.find(fmt::format("{:+.4f} ± {:.4f}", r.find(nav::Method::Ekf)->track.back().bias_north_m_s,
                               0.05 / 12.0)),
            std::string::npos)
      << t;
  EXPECT_NE(t.find("chain \"Syledis\""), std::string::npos) << "chains by name";
  EXPECT_NE(t.find("+1.500e-05 ± 2.000e-06"), std::string::npos) << t;
  EXPECT_NE(t.find("+12.250 ± 1.500 m"), std::string::npos) << t;
  EXPECT_NE(t.find("30 LOPs"), std::string::npos);
  EXPECT_NE(t.find("skipped"), std::string::npos);
  EXPECT_NE(t.find("LOP lops.csv:31 at 99999.0 s: outside the DR span"), std::string::npos) << t;
  // backward, fix-closure and rts reuse the observations of their forward runs
  EXPECT_NE(t.find("as bias-I"), std::string::npos) << t;
  EXPECT_NE(t.find("as ekf"), std::string::npos) << t;
  EXPECT_NE(t.find("per minute"), std::string::npos);
  EXPECT_NE(t.find("note: initial position sigma 100 m (default)"), std::string::npos);
  EXPECT_NE(t.find("warning: no LOP between"), std::string::npos);
  // The method table is aligned: its rows are equally long up to the last column.
  const auto lines = lines_of(t);
  const auto head = std::find_if(lines.begin(), lines.end(),
                                 [](const std::string& l) { return l.rfind("method", 0) == 0; });
  ASSERT_NE(head, lines.end());
  const std::size_t col = head->find("mean NEES") + std::string("mean NEES").size();
  for (auto it = head + 1; it != head + 1 + static_cast<long>(r.methods.size()); ++it) {
    // Everything before the NEES column's end is ASCII here, so bytes are columns.
    EXPECT_EQ(it->find_first_of("0123456789an", col - 1), col - 1) << *it;
  }
}

TEST(NavText, WithoutTruthSaysSo) {
  const std::string t = nav_summary_text(make_result(3, false));
  EXPECT_NE(t.find("No truth"), std::string::npos);
  EXPECT_EQ(t.find("RMS (m)"), std::string::npos);
  // Each method's position σ without truth (make_track: var x 25 + 0.1k, var y 16 + 0.2k):
  // final √25.2 = 5.02, √16.4 = 4.05; σ_h = √(41 + 0.3k): mean 6.43, max √41.6 = 6.45.
  EXPECT_NE(t.find("final σx (m)"), std::string::npos) << t;
  const auto lines = lines_of(t);
  const auto row = std::find_if(lines.begin(), lines.end(),
                                [](const std::string& l) { return l.rfind("ekf ", 0) == 0; });
  ASSERT_NE(row, lines.end()) << t;
  std::size_t at = 0;
  for (const char* v : {" 5.02 ", " 4.05 ", " 6.43 ", " 6.45 "}) {
    at = row->find(v, at);
    ASSERT_NE(at, std::string::npos) << v << " in " << *row;
  }
  EXPECT_NO_THROW((void)nav_summary_text(nav::Result{}));
}

// ---- report document -----------------------------------------------------------------------

TEST(NavDocument, HasEverySectionAndRenders) {
  const nav::Result r = make_result();
  const Document d = nav_document(r, "Line 7 <test>");
  EXPECT_EQ(d.title, "Line 7 <test>");
  for (const char* id : {"summary", "track", "errors", "bias", "rejected", "notes"})
    EXPECT_NE(find_section(d, id), nullptr) << id;
  // Track, error curves, bias north and east.
  EXPECT_EQ(plot_count(d), 4u);
  EXPECT_EQ(blocks<Plot>(*find_section(d, "errors")).size(), 1u);
  EXPECT_EQ(blocks<Plot>(*find_section(d, "bias")).size(), 2u);
  const auto tables = blocks<Table>(*find_section(d, "summary"));
  ASSERT_GE(tables.size(), 2u);
  EXPECT_EQ(tables[0]->rows.size(), r.methods.size());
  EXPECT_EQ(tables[0]->columns[1], "RMS (m)");
  EXPECT_EQ(tables[0]->columns[3], "mean NEES");
  EXPECT_EQ(tables[1]->rows.size(), 2u) << "the chain parameters";
  const auto rejected = blocks<Table>(*find_section(d, "rejected"));
  ASSERT_EQ(rejected.size(), 2u) << "rejected and skipped";
  EXPECT_EQ(rejected[0]->rows.size(), r.rejected.size());
  EXPECT_EQ(rejected[1]->rows.size(), r.skipped.size());
  const auto notes = blocks<Notes>(*find_section(d, "notes"));
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_TRUE(notes[0]->warning);

  // The error plot has every method with truth on one plot, bins without truth left out.
  const Plot& errors = *blocks<Plot>(*find_section(d, "errors"))[0];
  const json& ev = errors.spec["data"]["values"];
  EXPECT_EQ(ev.size(), 2 * r.methods.size());
  // The bias plots: the ±σ band only for the EKF and the smoother.
  const Plot& bias_n = *blocks<Plot>(*find_section(d, "bias"))[0];
  ASSERT_EQ(bias_n.spec["layer"].size(), 3u) << "bands of ekf and rts, then the lines";
  for (int layer : {0, 1}) {
    EXPECT_EQ(bias_n.spec["layer"][layer]["mark"]["type"], "area");
    const json& v = bias_n.spec["layer"][layer]["data"]["values"];
    EXPECT_EQ(v.size(), 12u);
    for (const json& p : v) EXPECT_EQ(p["m"], layer == 0 ? "ekf" : "rts") << p;
    EXPECT_NEAR(v[3]["hi"].get<double>() - v[3]["lo"].get<double>(), 2 * 0.05 / 4.0, 2e-5);
  }
  std::set<std::string> with_bias;
  for (const json& v : bias_n.spec["layer"][2]["data"]["values"]) with_bias.insert(v["m"]);
  EXPECT_EQ(with_bias, (std::set<std::string>{"sequential-bias-I", "sequential-bias-II", "backward",
                                              "ekf", "rts"}));

  if (html_reports_available()) {
    const std::string html = render_html(d);
    for (const char* id : {"summary", "track", "errors", "bias", "rejected", "notes"})
      EXPECT_NE(html.find(fmt::format("<section id=\"{}\">", id)), std::string::npos) << id;
    EXPECT_NE(html.find("Line 7 &lt;test&gt;"), std::string::npos);
  } else {
    EXPECT_THROW((void)render_html(d), Error);
  }
}

TEST(NavDocument, TrackPlotHasOneScaleOnBothAxesAndIsDecimated) {
  const std::size_t n = 5001;
  const nav::Result r = make_result(n);
  const Document d = nav_document(r, "long line");
  const Plot& track = *blocks<Plot>(*find_section(d, "track"))[0];
  const json& x = track.spec["encoding"]["x"]["scale"]["domain"];
  const json& y = track.spec["encoding"]["y"]["scale"]["domain"];
  const double mpp_x = (x[1].get<double>() - x[0].get<double>()) / track.spec["width"].get<double>();
  const double mpp_y = (y[1].get<double>() - y[0].get<double>()) / track.spec["height"].get<double>();
  EXPECT_NEAR(mpp_x / mpp_y, 1.0, 1e-9) << "metres per pixel";
  EXPECT_EQ(track.spec["encoding"]["x"]["field"], "e") << "east across";
  EXPECT_EQ(track.spec["encoding"]["y"]["field"], "n") << "north up";
  // At most 2000 points per method, the first and the last among them.
  std::map<std::string, std::vector<std::size_t>> drawn;
  for (const json& v : track.spec["data"]["values"]) drawn[v["m"]].push_back(v["i"].get<std::size_t>());
  EXPECT_EQ(drawn.size(), r.methods.size());
  for (const auto& [m, idx] : drawn) {
    EXPECT_LE(idx.size(), 2000u) << m;
    EXPECT_GT(idx.size(), 1000u) << m;
    EXPECT_EQ(idx.front(), 0u);
    EXPECT_EQ(idx.back(), n - 1);
  }
  // Every drawn point lies inside the domains.
  for (const json& v : track.spec["data"]["values"]) {
    EXPECT_GE(v["e"].get<double>(), x[0].get<double>());
    EXPECT_LE(v["e"].get<double>(), x[1].get<double>());
    EXPECT_GE(v["n"].get<double>(), y[0].get<double>());
    EXPECT_LE(v["n"].get<double>(), y[1].get<double>());
  }
  EXPECT_NE(track.caption.find("One epoch in 3"), std::string::npos) << track.caption;
  EXPECT_NE(track.caption.find("2000"), std::string::npos) << track.caption;
  for (const Plot* p : blocks<Plot>(*find_section(d, "bias")))
    EXPECT_NE(p->caption.find("One epoch in 3"), std::string::npos) << p->caption;
}

TEST(NavDocument, WithoutTruthHasNoErrorCurves) {
  const Document d = nav_document(make_result(4, false), "no truth");
  ASSERT_NE(find_section(d, "errors"), nullptr);
  EXPECT_TRUE(blocks<Plot>(*find_section(d, "errors")).empty());
  EXPECT_EQ(blocks<Paragraph>(*find_section(d, "errors")).size(), 1u);
  EXPECT_EQ(plot_count(d), 3u);
  EXPECT_EQ(blocks<Table>(*find_section(d, "summary"))[0]->columns[1], "final σx (m)");
  EXPECT_EQ(blocks<Table>(*find_section(d, "summary"))[0]->columns[5], "final bias N (m/s)");
  const Document empty = nav_document(nav::Result{}, "empty");
  EXPECT_NE(find_section(empty, "notes"), nullptr);
  if (html_reports_available()) {
    EXPECT_NO_THROW((void)render_html(empty));
  }
}

TEST(NavDocument, LongListsAreCutWithANote) {
  nav::Result r = make_result(4);
  const nav::RejectedObservation one = r.rejected[0];
  r.rejected.assign(1005, one);
  r.skipped.assign(205, r.skipped[0]);
  const Document d = nav_document(r, "many");
  const auto tables = blocks<Table>(*find_section(d, "rejected"));
  ASSERT_EQ(tables.size(), 2u);
  EXPECT_EQ(tables[0]->rows.size(), 1000u);
  EXPECT_NE(tables[0]->note.find("1000 of 1005"), std::string::npos) << tables[0]->note;
  EXPECT_EQ(tables[1]->rows.size(), 200u);
  EXPECT_NE(tables[1]->note.find("200 of 205"), std::string::npos) << tables[1]->note;
  // The CSV and the JSON keep every one.
  EXPECT_EQ(lines_of(nav_rejected_csv(r)).size(), 1006u);
  EXPECT_EQ(nav_to_json(r)["skipped"].size(), 205u);
  const std::string t = nav_summary_text(r);
  EXPECT_NE(t.find("… and 195 more"), std::string::npos);
}

TEST(NavText, ALongLineShowsTheFirstTwoHoursPerMinute) {
  nav::Result r = make_result(4);
  for (auto& m : r.methods) m.errors->per_minute_rms_m.assign(150, 3.0);
  const std::string t = nav_summary_text(r);
  EXPECT_NE(t.find("the first 120 of 150 minutes"), std::string::npos);
  EXPECT_NE(t.find("\n  119 "), std::string::npos);
  EXPECT_EQ(t.find("\n  120 "), std::string::npos);
  EXPECT_EQ(nav_to_json(r)["methods"]["rts"]["per_minute_rms_m"].size(), 150u);
  EXPECT_EQ(nav_to_json(r)["method_order"][0], "dead-reckoning");
  EXPECT_EQ(nav_to_json(r)["method_order"].back(), "rts");
}

// ---- self-checks (issue 32) ------------------------------------------------------------------

TEST(NavSelfChecks, AMarkedMethodSaysSoInEveryOutput) {
  nav::Result r = make_result(12, false);
  nav::MethodResult* bi = nullptr;
  for (auto& m : r.methods)
    if (m.method == nav::Method::SequentialBiasI) bi = &m;
  ASSERT_NE(bi, nullptr);
  nav::ConsistencyAlarm a;
  a.status = nav::MethodStatus::Diverged;
  a.check = "fix-run";
  a.from_epoch = 2;
  a.to_epoch = 11;
  a.from_s = bi->track[2].time_s;
  a.to_s = bi->track[11].time_s;
  a.reason = "8 consecutive fixes (of 8) off the track";
  bi->consistency.status = nav::MethodStatus::Diverged;
  bi->consistency.alarms.push_back(a);
  bi->consistency.longest_fix_run = 8;
  // JSON
  const json j = nav_to_json(r);
  EXPECT_EQ(j["methods"]["sequential-bias-I"]["status"], "diverged");
  EXPECT_EQ(j["methods"]["sequential-bias-I"]["sigma_valid"], false);
  const json& al = j["methods"]["sequential-bias-I"]["consistency"]["alarms"];
  ASSERT_EQ(al.size(), 1u);
  EXPECT_EQ(al[0]["check"], "fix-run");
  EXPECT_EQ(al[0]["from_epoch"], 2);
  EXPECT_EQ(al[0]["to_epoch"], 11);
  EXPECT_DOUBLE_EQ(al[0]["from_s"].get<double>(), 36010.1);
  EXPECT_EQ(j["methods"]["ekf"]["status"], "consistent");
  EXPECT_EQ(j["methods"]["ekf"]["sigma_valid"], true);
  // text: the status column and "(not valid)" beside the σ of the marked method only
  const std::string t = nav_summary_text(r);
  const auto lines = lines_of(t);
  const auto row = [&](const char* name) {
    return *std::find_if(lines.begin(), lines.end(),
                         [&](const std::string& l) { return l.rfind(std::string(name) + " ", 0) == 0; });
  };
  EXPECT_NE(row("sequential-bias-I").find("(not valid)"), std::string::npos) << t;
  EXPECT_NE(row("sequential-bias-I").find("diverged 36010.1–36055.1 s (fix-run)"), std::string::npos) << t;
  EXPECT_EQ(row("ekf").find("(not valid)"), std::string::npos) << t;
  EXPECT_NE(row("ekf").find("consistent"), std::string::npos) << t;
  // track CSV: a warning line for the marked method, none for a consistent one
  EXPECT_NE(nav_track_csv(r, nav::Method::SequentialBiasI).find("# WARNING: sequential-bias-I diverged"),
            std::string::npos);
  EXPECT_EQ(nav_track_csv(r, nav::Method::Ekf).find("WARNING"), std::string::npos);
  // HTML document: the status column and the table of failed checks
  const Document d = nav_document(r, "line");
  const auto tables = blocks<Table>(*find_section(d, "summary"));
  ASSERT_GE(tables.size(), 2u);
  EXPECT_EQ(tables[0]->columns.back(), "status");
  EXPECT_EQ(tables[1]->title, "Self-checks that failed");
  ASSERT_EQ(tables[1]->rows.size(), 1u);
  EXPECT_EQ(tables[1]->rows[0][0], "sequential-bias-I");
  EXPECT_EQ(tables[1]->rows[0][1], "diverged");
}
