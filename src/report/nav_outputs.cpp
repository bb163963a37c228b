#include "meridian/report/nav_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "json_number.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/geodesy/grid.hpp"
#include "meridian/report/format.hpp"
#include "nav_support.hpp"

namespace meridian::report {
namespace {

using detail::json_number;
using nlohmann::json;
using namespace nav_detail;

// ---- numbers -----------------------------------------------------------------------------

// The shortest decimal that reads back as the same double; empty when not finite.
std::string nav_csv_number(double v) { return std::isfinite(v) ? fmt::format("{}", v) : std::string(); }

// The GeoJSON properties keep the order they are written in.
using ojson = nlohmann::ordered_json;
ojson nav_geo_number(double v) { return std::isfinite(v) ? ojson(v) : ojson(); }

// Rounded to 1e-9 degree (0.1 mm): the shortest form of the rounded double has at most 9
// decimals.
double nav_round_deg(double deg) { return std::round(deg * 1e9) / 1e9; }

// {lat_deg, lon_deg} of a plane point, lon in [-180, 180]; InputError when not geographic.
std::array<double, 2> nav_geographic(const geodesy::TransverseMercatorGrid& grid, const nav::TrackPoint& p,
                                     nav::Method m, std::size_t epoch) {
  const geodesy::GeographicPoint q = grid.reverse(p.x_north_m, p.y_east_m);
  double lat = units::rad_to_deg(q.lat_rad), lon = units::rad_to_deg(q.lon_rad);
  if (!std::isfinite(lat) || !std::isfinite(lon) || std::fabs(lat) > 90.0)
    throw InputError(fmt::format(
        "the projection gives no geographic position for epoch {} of method {} (x {} m, y {} m): "
        "latitude {}°, longitude {}°",
        epoch, nav::to_string(m), p.x_north_m, p.y_east_m, lat, lon));
  lon = std::remainder(lon, 360.0);  // [-180, 180]
  return {lat, lon};
}

// ---- text --------------------------------------------------------------------------------

// Display width of UTF-8 text in code points (every character here is one column wide).
std::size_t nav_text_width(const std::string& s) {
  std::size_t n = 0;
  for (unsigned char c : s)
    if ((c & 0xC0u) != 0x80u) ++n;
  return n;
}

std::string nav_pad(const std::string& s, std::size_t width, bool right) {
  const std::size_t w = nav_text_width(s);
  if (w >= width) return s;
  const std::string fill(width - w, ' ');
  return right ? fill + s : s + fill;
}

// Rows of cells as aligned columns: the first `left` columns left-aligned, the others
// right-aligned.
std::string nav_columns(const std::vector<std::vector<std::string>>& rows, const std::string& indent,
                        std::size_t left = 1) {
  std::vector<std::size_t> width;
  for (const auto& row : rows)
    for (std::size_t c = 0; c < row.size(); ++c) {
      if (width.size() <= c) width.push_back(0);
      width[c] = std::max(width[c], nav_text_width(row[c]));
    }
  std::string out;
  for (const auto& row : rows) {
    std::string line = indent;
    for (std::size_t c = 0; c < row.size(); ++c)
      line += (c == 0 ? "" : "  ") + nav_pad(row[c], width[c], c >= left);
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line + "\n";
  }
  return out;
}

std::string nav_value_sigma(double v, double sigma, int decimals) {
  const double s = stated_sigma(sigma);
  return std::isfinite(s) ? fmt::format("{:+.{}f} ± {:.{}f}", v, decimals, s, decimals)
                          : fmt::format("{:+.{}f}", v, decimals);
}

std::string nav_parameter_text(const nav::ChainParameter& p) {
  const bool scale = p.name == "scale";
  const std::string sigma = std::isfinite(p.sigma) ? (scale ? fmt::format("{:.3e}", p.sigma)
                                                            : fmt::format("{:.3f}", p.sigma))
                                                   : std::string("n/a");
  return scale ? fmt::format("{:+.3e} ± {}", p.value, sigma)
               : fmt::format("{:+.3f} ± {} m", p.value, sigma);
}

std::string nav_rejected_text(const RejectionCounts& c) {
  std::string t;
  if (c.lops) t = fmt::format("{} LOP{}", c.lops, c.lops == 1 ? "" : "s");
  if (c.fixes) t += fmt::format("{}{} fix{}", t.empty() ? "" : ", ", c.fixes, c.fixes == 1 ? "" : "es");
  return t.empty() ? "0" : t;
}

// Short column heads of the per-minute table.
std::string nav_short_name(nav::Method m) {
  switch (m) {
    case nav::Method::DeadReckoning: return "DR";
    case nav::Method::SequentialNoBias: return "no-bias";
    case nav::Method::SequentialBiasI: return "bias-I";
    case nav::Method::SequentialBiasII: return "bias-II";
    case nav::Method::Backward: return "backward";
    case nav::Method::FixClosure: return "fix-closure";
    case nav::Method::Ekf: return "ekf";
    case nav::Method::Rts: return "rts";
  }
  return nav::to_string(m);
}

constexpr std::size_t kMaxTextBins = 120;   // per-minute rows in the text (a 2-hour line)
constexpr std::size_t kMaxTextListed = 10;  // skipped observations listed by name

// The line: epochs, time span, observations used, rejected and skipped.
std::string nav_line_text(const nav::Result& r) {
  const nav::MethodResult* any = nullptr;
  for (const auto& m : r.methods)
    if (!m.track.empty()) {
      any = &m;
      break;
    }
  std::string t = fmt::format("Navigation: {} epoch{}", r.epochs, r.epochs == 1 ? "" : "s");
  if (any)
    t += fmt::format(", {:.1f} … {:.1f} s ({:.1f} min)", any->track.front().time_s,
                     any->track.back().time_s,
                     (any->track.back().time_s - any->track.front().time_s) / 60.0);
  t += fmt::format("\nused: {} LOP{}, {} fix{}; rejected: {} (by all methods); skipped: {}\n",
                   r.lops_used, r.lops_used == 1 ? "" : "s", r.fixes_used,
                   r.fixes_used == 1 ? "" : "es", r.rejected.size(), r.skipped.size());
  return t;
}

// One row of the methods table: errors against truth (or the σ without truth), final bias,
// rejections.
std::vector<std::string> nav_method_row(const nav::Result& r, const nav::MethodResult& m, bool truth) {
  std::vector<std::string> row{nav::to_string(m.method)};
  if (truth) {
    if (m.errors) {
      row.push_back(fmtx::num(m.errors->rms_m, 2));
      row.push_back(fmtx::num(m.errors->max_error_m, 2));
      row.push_back(fmtx::num(m.errors->mean_nees, 2));
    } else {
      row.insert(row.end(), {"n/a", "n/a", "n/a"});
    }
  } else {
    const SigmaSummary sg = sigma_summary(m);
    for (double v : {sg.final_x, sg.final_y, sg.mean_h, sg.max_h}) row.push_back(nav_sigma_cell(m, fmtx::num(v, 2)));
  }
  if (!estimates_bias(m.method) || m.track.empty()) {
    row.insert(row.end(), {"not estimated", "not estimated"});
  } else {
    const nav::TrackPoint& last = m.track.back();
    row.push_back(nav_value_sigma(last.bias_north_m_s, last.sigma_bias_north_m_s, 4));
    row.push_back(nav_value_sigma(last.bias_east_m_s, last.sigma_bias_east_m_s, 4));
  }
  const auto from = observations_of(m.method);
  row.push_back(from ? "as " + nav_short_name(*from) : nav_rejected_text(rejection_counts(r, m.method)));
  row.push_back(nav_status_text(m));
  return row;
}

// The methods side by side, with what the columns mean.
std::string nav_methods_text(const nav::Result& r, bool truth) {
  std::vector<std::vector<std::string>> rows;
  if (truth)
    rows.push_back({"method", "RMS (m)", "max (m)", "mean NEES", "final bias N (m/s)",
                    "final bias E (m/s)", "rejected", "status"});
  else
    rows.push_back({"method", "final σx (m)", "final σy (m)", "mean σ (m)", "max σ (m)",
                    "final bias N (m/s)", "final bias E (m/s)", "rejected", "status"});
  for (const auto& m : r.methods) rows.push_back(nav_method_row(r, m, truth));
  std::string t = "\n" + nav_columns(rows, "");
  if (truth)
    t += "RMS and max: horizontal position error against truth; mean NEES of (x, y): 2 for a "
         "consistent σ.\n";
  else
    t += "No truth: no error statistics. σ: the final σ of x and y; mean and max over the line of "
         "the horizontal σ = √(σx² + σy²) (the notes say which methods' σ are rigorous).\n";
  t += "Bias: the correction to the DR velocity at the last epoch (± σ where the method states "
       "one).\n";
  t += "Rejected: by the method's own screening; backward and fix-closure use the observations "
       "sequential-bias-I accepted, rts those the ekf accepted.\n";
  t += "Status: the method's self-checks from the data alone (fix misclosures, rejected share, "
       "innovation spread; no truth): diverged or inconsistent over the times given, its σ not "
       "valid there (\"(not valid)\" beside a σ).\n";
  for (const auto& m : r.methods)
    for (const auto& a : m.consistency.alarms)
      t += fmt::format("  {} {} {:.1f}–{:.1f} s (epochs {}–{}), {}: {}\n", nav::to_string(m.method),
                       nav::to_string(a.status), a.from_s, a.to_s, a.from_epoch, a.to_epoch, a.check, a.reason);
  std::vector<std::vector<std::string>> params;
  for (const auto& m : r.methods)
    for (const auto& p : m.parameters)
      params.push_back({nav::to_string(m.method), chain_label(p), p.name, nav_parameter_text(p)});
  if (!params.empty()) t += "\nchain parameters (value ± σ)\n" + nav_columns(params, "  ", 3);
  return t;
}

// The per-minute RMS table of the methods with truth (empty without bins).
std::string nav_per_minute_text(const nav::Result& r) {
  std::size_t bins = 0;
  for (const auto& m : r.methods)
    if (m.errors) bins = std::max(bins, m.errors->per_minute_rms_m.size());
  if (bins == 0) return {};
  std::vector<std::vector<std::string>> table;
  std::vector<std::string> head{"minute"};
  std::string legend;
  for (const auto& m : r.methods)
    if (m.errors) {
      head.push_back(nav_short_name(m.method));
      if (nav_short_name(m.method) != nav::to_string(m.method))
        legend += fmt::format("{}{} = {}", legend.empty() ? "" : ", ", nav_short_name(m.method),
                              nav::to_string(m.method));
    }
  table.push_back(head);
  for (std::size_t j = 0; j < std::min(bins, kMaxTextBins); ++j) {
    std::vector<std::string> row{fmt::format("{}", j)};
    for (const auto& m : r.methods)
      if (m.errors)
        row.push_back(j < m.errors->per_minute_rms_m.size() ? fmtx::num(m.errors->per_minute_rms_m[j], 1)
                                                            : std::string("n/a"));
    table.push_back(row);
  }
  double bin_s = 60.0;
  for (const auto& m : r.methods)
    if (m.errors) bin_s = m.errors->bin_s;
  std::string t =
      bin_s == 60.0
          ? std::string("\nRMS position error per minute (m; minute j: j ≤ t − t₀ < j + 1 min; n/a: no truth)\n")
          : fmt::format("\nRMS position error per bin of {:g} s (m; bin j: j·{:g} ≤ t − t₀ < (j + 1)·{:g} s; the "
                        "column says \"minute\"; n/a: no truth)\n",
                        bin_s, bin_s, bin_s);
  t += nav_columns(table, "  ");
  if (bins > kMaxTextBins)
    t += fmt::format("  (the first {} of {} minutes; every minute is in the JSON)\n", kMaxTextBins, bins);
  if (!legend.empty()) t += "  " + legend + "\n";
  return t;
}

// Rejections counted, skipped observations listed, notes and warnings.
std::string nav_observations_and_notes_text(const nav::Result& r) {
  std::string t;
  if (!r.rejected.empty()) {
    std::size_t lops = 0;
    for (const auto& o : r.rejected) lops += o.kind == nav::RejectedObservation::Kind::Lop;
    t += fmt::format("\nrejected: {} LOP and {} fix rejection{} over all methods (the rejected "
                     "CSV lists each)\n",
                     lops, r.rejected.size() - lops, r.rejected.size() == 1 ? "" : "s");
  }
  if (!r.skipped.empty()) {
    t += fmt::format("\nskipped (no method used them): {}\n", r.skipped.size());
    for (std::size_t i = 0; i < std::min(r.skipped.size(), kMaxTextListed); ++i) {
      const auto& s = r.skipped[i];
      t += fmt::format("  {} at {:.1f} s: {}\n", observation_label(s.kind, s.index, s.source), s.time_s,
                       s.reason);
    }
    if (r.skipped.size() > kMaxTextListed)
      t += fmt::format("  … and {} more (see the JSON)\n", r.skipped.size() - kMaxTextListed);
  }
  if (!r.notes.empty() || !r.warnings.empty()) t += "\n";
  for (const std::string& n : r.notes) t += "note: " + n + "\n";
  for (const std::string& w : r.warnings) t += "warning: " + w + "\n";
  return t;
}

}  // namespace

std::string nav_summary_text(const nav::Result& r) {
  const bool truth = std::any_of(r.methods.begin(), r.methods.end(),
                                 [](const nav::MethodResult& m) { return m.errors.has_value(); });
  std::string t = nav_line_text(r) + nav_methods_text(r, truth);
  if (truth) t += nav_per_minute_text(r);
  return t + nav_observations_and_notes_text(r);
}

json nav_to_json(const nav::Result& r) {
  json methods = json::object();
  json order = json::array();
  for (const auto& m : r.methods) {
    json j;
    j["epochs"] = m.track.size();
    if (m.errors) {
      j["rms_m"] = json_number(m.errors->rms_m);
      j["max_error_m"] = json_number(m.errors->max_error_m);
      j["mean_nees"] = json_number(m.errors->mean_nees);
      j["error_epochs"] = m.errors->epochs;
      json bins = json::array();
      for (double v : m.errors->per_minute_rms_m) bins.push_back(json_number(v));
      j["per_minute_rms_m"] = bins;
      j["bin_s"] = m.errors->bin_s;
    } else {
      j["rms_m"] = j["max_error_m"] = j["mean_nees"] = j["error_epochs"] = nullptr;
      j["per_minute_rms_m"] = json::array();
    }
    j["estimates_bias"] = estimates_bias(m.method);
    const SigmaSummary sg = sigma_summary(m);
    j["sigma_horizontal_mean_m"] = json_number(sg.mean_h);
    j["sigma_horizontal_max_m"] = json_number(sg.max_h);
    const auto from = observations_of(m.method);
    j["observations_of"] = from ? json(nav::to_string(*from)) : json(nullptr);
    if (m.track.empty()) {
      j["bias_north_m_s"] = j["bias_east_m_s"] = j["sigma_bias_north_m_s"] =
          j["sigma_bias_east_m_s"] = j["final_position"] = nullptr;
    } else {
      const nav::TrackPoint& p = m.track.back();
      j["bias_north_m_s"] = json_number(p.bias_north_m_s);
      j["bias_east_m_s"] = json_number(p.bias_east_m_s);
      j["sigma_bias_north_m_s"] = json_number(stated_sigma(p.sigma_bias_north_m_s));
      j["sigma_bias_east_m_s"] = json_number(stated_sigma(p.sigma_bias_east_m_s));
      j["final_position"] = {{"time_s", json_number(p.time_s)},
                             {"x_north_m", json_number(p.x_north_m)},
                             {"y_east_m", json_number(p.y_east_m)},
                             {"sigma_x_m", json_number(p.sigma_x_m())},
                             {"sigma_y_m", json_number(p.sigma_y_m())},
                             {"cov_xy_m2", json_number(p.covariance(0, 1))}};
    }
    json params = json::array();
    for (const auto& q : m.parameters)
      params.push_back({{"chain", q.chain},
                        {"chain_name", q.chain_name},
                        {"name", q.name},
                        {"value", json_number(q.value)},
                        {"sigma", json_number(q.sigma)}});
    j["parameters"] = params;
    const RejectionCounts c = rejection_counts(r, m.method);
    j["rejected_lops"] = c.lops;
    j["flagged_fixes"] = c.fixes;
    const nav::Consistency& cs = m.consistency;
    j["status"] = nav::to_string(cs.status);
    j["sigma_valid"] = cs.sigma_valid();
    json alarms = json::array();
    for (const auto& a : cs.alarms)
      alarms.push_back({{"status", nav::to_string(a.status)},
                        {"check", a.check},
                        {"from_s", json_number(a.from_s)},
                        {"to_s", json_number(a.to_s)},
                        {"from_epoch", a.from_epoch},
                        {"to_epoch", a.to_epoch},
                        {"reason", a.reason}});
    j["consistency"] = {{"status", nav::to_string(cs.status)},
                        {"sigma_valid", cs.sigma_valid()},
                        {"alarms", alarms},
                        {"fixes_tested", cs.fixes_tested},
                        {"fixes_outlying", cs.fixes_outlying},
                        {"longest_fix_run", cs.longest_fix_run},
                        {"fix_sigma_ratio", json_number(cs.fix_sigma_ratio)},
                        {"lops_tested", cs.lops_tested},
                        {"lops_rejected", cs.lops_rejected},
                        {"max_rejected_share", json_number(cs.max_rejected_share)},
                        {"max_innovation_ratio", json_number(cs.max_innovation_ratio)}};
    methods[nav::to_string(m.method)] = j;
    order.push_back(nav::to_string(m.method));
  }
  json rejected = json::array();
  for (const auto& o : r.rejected)
    rejected.push_back({{"kind", kind_name(o.kind)},
                        {"index", o.index},
                        {"method", nav::to_string(o.method)},
                        {"time_s", json_number(o.time_s)},
                        {"misclosure_m", json_number(o.misclosure_m)},
                        {"statistic", json_number(o.statistic)},
                        {"reason", o.reason},
                        {"source", o.source}});
  json skipped = json::array();
  for (const auto& s : r.skipped)
    skipped.push_back({{"kind", kind_name(s.kind)},
                       {"index", s.index},
                       {"time_s", json_number(s.time_s)},
                       {"reason", s.reason},
                       {"source", s.source}});
  return {{"epochs", r.epochs},       {"lops_used", r.lops_used}, {"fixes_used", r.fixes_used},
          {"method_order", order},    {"methods", methods},       {"rejected", rejected},
          {"skipped", skipped},       {"notes", r.notes},         {"warnings", r.warnings}};
}

NavTrackColumns nav_track_columns(const nav::Result& r, nav::Method method, bool unstated_sigma_as_nan) {
  const nav::MethodResult& m = require_method(r, method);
  const std::optional<geodesy::TransverseMercatorGrid> grid =
      r.projection ? std::optional<geodesy::TransverseMercatorGrid>(*r.projection) : std::nullopt;
  NavTrackColumns c;
  c.names = {"time_s", "x_m", "y_m"};
  if (grid) c.names.insert(c.names.end(), {"lat_deg", "lon_deg"});
  c.names.insert(c.names.end(), {"sigma_x_m", "sigma_y_m", "cov_xy_m2", "bias_north_m_s", "bias_east_m_s",
                                 "sigma_bias_north_m_s", "sigma_bias_east_m_s"});
  c.values.assign(c.names.size(), std::vector<double>(m.track.size()));
  const auto bias_sigma = [&](double s) { return unstated_sigma_as_nan ? stated_sigma(s) : s; };
  for (std::size_t k = 0; k < m.track.size(); ++k) {
    const nav::TrackPoint& p = m.track[k];
    std::size_t i = 0;
    for (double v : {p.time_s, p.x_north_m, p.y_east_m}) c.values[i++][k] = v;
    if (grid)
      for (double v : nav_geographic(*grid, p, method, k)) c.values[i++][k] = v;
    for (double v : {p.sigma_x_m(), p.sigma_y_m(), p.covariance(0, 1), p.bias_north_m_s, p.bias_east_m_s,
                     bias_sigma(p.sigma_bias_north_m_s), bias_sigma(p.sigma_bias_east_m_s)})
      c.values[i++][k] = v;
    c.flags.push_back(p.flags);
  }
  return c;
}

std::string nav_track_csv(const nav::Result& r, nav::Method method) {
  const NavTrackColumns c = nav_track_columns(r, method, false);
  const std::size_t n = c.flags.size();
  std::string out = fmt::format("# meridian navigation track, method {}: {} epochs; x north, y east (m)\n",
                                nav::to_string(method), n);
  if (const nav::MethodResult& m = require_method(r, method); !m.consistency.sigma_valid())
    for (const auto& a : m.consistency.alarms)
      out += fmt::format("# WARNING: {} {} from {:.1f} s to {:.1f} s ({}): its positions and σ are not valid there\n",
                         nav::to_string(method), nav::to_string(a.status), a.from_s, a.to_s, a.check);
  out += "# flags: sum of 1 LOP used, 2 LOP rejected, 4 fix combined, 8 fix flagged and not combined\n";
  out += fmt::format("{},flags\n", fmt::join(c.names, ","));
  for (std::size_t k = 0; k < n; ++k) {
    for (const std::vector<double>& column : c.values) out += nav_csv_number(column[k]) + ',';
    out += std::to_string(c.flags[k]) + '\n';
  }
  return out;
}

std::string nav_track_geojson(const nav::Result& r, const std::vector<nav::Method>& methods) {
  if (!r.projection)
    throw InputError(
        "GeoJSON needs geographic coordinates (longitude, latitude), and this job has no map "
        "projection: give the job's projection (or geographic input) to write GeoJSON, or write "
        "the track CSV in plane coordinates instead");
  const geodesy::TransverseMercatorGrid grid(*r.projection);
  std::vector<const nav::MethodResult*> chosen;
  if (methods.empty())
    for (const auto& m : r.methods) chosen.push_back(&m);
  else
    for (nav::Method m : methods) chosen.push_back(&require_method(r, m));

  // Written as text, not as a JSON tree: a 10 Hz day is 864 000 positions per method. The
  // properties are small and go through the JSON library.
  std::string out = R"({"type":"FeatureCollection","features":[)";
  bool first_feature = true;
  auto feature = [&](const std::string& geometry, const ojson& properties) {
    out += first_feature ? "\n" : ",\n";
    first_feature = false;
    out += R"({"type":"Feature","geometry":)" + geometry + R"(,"properties":)" + properties.dump() + "}";
  };
  auto position = [](double lon, double lat) {
    return fmt::format("[{},{}]", nav_round_deg(lon), nav_round_deg(lat));
  };
  for (const nav::MethodResult* m : chosen) {
    // Positions, cut at the antimeridian (RFC 7946 §3.1.9) into parts, each a LineString.
    std::vector<std::string> parts(1);
    std::array<double, 2> prev{};
    for (std::size_t k = 0; k < m->track.size(); ++k) {
      const std::array<double, 2> ll = nav_geographic(grid, m->track[k], m->method, k);
      if (k > 0 && std::fabs(ll[1] - prev[1]) > 180.0) {
        const double edge = prev[1] > 0 ? 180.0 : -180.0;
        const double lon_b = ll[1] + (prev[1] > 0 ? 360.0 : -360.0);  // unwrapped
        const double f = (edge - prev[1]) / (lon_b - prev[1]);
        const double lat_c = prev[0] + f * (ll[0] - prev[0]);
        parts.back() += "," + position(edge, lat_c);
        parts.push_back(position(-edge, lat_c));
      }
      parts.back() += (parts.back().empty() ? "" : ",") + position(ll[1], ll[0]);
      prev = ll;
    }
    std::string geometry = "null";
    if (m->track.size() == 1) {
      geometry = R"({"type":"Point","coordinates":)" + parts[0] + "}";
    } else if (parts.size() == 1 && m->track.size() > 1) {
      geometry = R"({"type":"LineString","coordinates":[)" + parts[0] + "]}";
    } else if (parts.size() > 1) {
      geometry = R"({"type":"MultiLineString","coordinates":[)";
      for (std::size_t i = 0; i < parts.size(); ++i) geometry += (i ? ",[" : "[") + parts[i] + "]";
      geometry += "]}";
    }
    ojson props = {{"feature", "track"},
                   {"method", nav::to_string(m->method)},
                   {"epochs", m->track.size()},
                   {"status", nav::to_string(m->consistency.status)},
                   {"sigma_valid", m->consistency.sigma_valid()}};
    if (!m->track.empty()) {
      props["start_time_s"] = nav_geo_number(m->track.front().time_s);
      props["end_time_s"] = nav_geo_number(m->track.back().time_s);
    }
    if (m->errors && std::isfinite(m->errors->rms_m)) props["rms_m"] = m->errors->rms_m;
    feature(geometry, props);
  }
  for (const auto& o : r.rejected) {
    const auto it = std::find_if(chosen.begin(), chosen.end(),
                                 [&](const nav::MethodResult* m) { return m->method == o.method; });
    if (it == chosen.end() || (*it)->track.empty()) continue;
    const std::size_t k = nearest_epoch((*it)->track, o.time_s);
    const std::array<double, 2> ll = nav_geographic(grid, (*it)->track[k], o.method, k);
    feature(R"({"type":"Point","coordinates":)" + position(ll[1], ll[0]) + "}",
            ojson{{"feature", "rejected"},
                  {"kind", kind_name(o.kind)},
                  {"index", o.index},
                  {"method", nav::to_string(o.method)},
                  {"time_s", nav_geo_number(o.time_s)},
                  {"misclosure_m", nav_geo_number(o.misclosure_m)},
                  {"statistic", nav_geo_number(o.statistic)},
                  {"reason", o.reason}});
  }
  return out + "\n]}\n";
}

std::string nav_rejected_csv(const nav::Result& r) {
  std::string out = "kind,index,method,time_s,misclosure_m,statistic,reason,source\n";
  const auto quoted = [](const std::string& text) {
    std::string q = "\"";
    for (char c : text) {
      if (c == '"') q += "\"\"";
      else if (c == '\n' || c == '\r') q += ' ';
      else q += c;
    }
    return q + '"';
  };
  for (const auto& o : r.rejected)
    out += fmt::format("{},{},{},{},{},{},{},{}\n", kind_name(o.kind), o.index, nav::to_string(o.method),
                       nav_csv_number(o.time_s), nav_csv_number(o.misclosure_m),
                       nav_csv_number(o.statistic), quoted(o.reason), quoted(o.source));
  return out;
}

}  // namespace meridian::report
