// A survey line as observed → the plane of the methods → process (nav/survey_line.hpp).
#include "meridian/nav/survey_line.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <set>
#include <utility>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "prepared.hpp"

namespace meridian::nav {
namespace {

constexpr double kDeg = units::kDegree;

std::string at(const char* array, std::size_t k, const char* member) {
  return *member ? fmt::format("{}[{}].{}", array, k, member) : fmt::format("{}[{}]", array, k);
}

/// The plane of a line: its grid, when it has one.
struct Plane {
  std::optional<geodesy::TransverseMercatorGrid> grid;

  /// `p` in the plane with γ and k there (γ = 0, k = 1 without a grid); InputError at `field`
  /// when the grid cannot take it.
  geodesy::GridPoint forward(const Position& p, const std::string& field) const {
    try {
      if (p.geographic) return grid->forward(p.lat_rad, p.lon_rad);
      geodesy::GridPoint g;
      g.x_north_m = p.x_north_m, g.y_east_m = p.y_east_m;
      if (grid) {
        const geodesy::GeographicPoint q = grid->reverse(p.x_north_m, p.y_east_m);
        g.convergence_rad = q.convergence_rad, g.scale = q.scale;
      }
      return g;
    } catch (Error& e) {
      throw InputError(e.message(), {{}, {}, field});
    }
  }
};

/// Rotation of a true (north, east) vector into the grid with the scale: k·R(−γ).
Eigen::Matrix2d to_grid(double gamma, double k) {
  const double c = std::cos(gamma), s = std::sin(gamma);
  Eigen::Matrix2d m;
  m << c, s, -s, c;
  return k * m;
}

// The line's projection, else a local transverse Mercator when any position is geographic;
// plane and geographic positions together need a projection.
Plane choose_plane(const SurveyLine& line, std::vector<std::string>& notes) {
  const std::string* first_geo_file = nullptr;
  const std::string* first_plane_file = nullptr;
  std::optional<double> first_geo_lon;
  const auto kind = [&](const std::string& file, const Position& p) {
    if (p.geographic) {
      if (!first_geo_file) first_geo_file = &file, first_geo_lon = p.lon_rad;
    } else if (!first_plane_file) {
      first_plane_file = &file;
    }
  };
  const std::string initial_name = line.initial_source.file + " (initial:)";
  if (line.initial) kind(initial_name, *line.initial);
  for (const auto& s : line.stations) kind(s.source.file, s.position);
  for (const auto& f : line.fixes) kind(f.source.file, f.position);
  // Truth is in time order; the first of its file decides (one file: one kind of position).
  const auto first_truth = std::min_element(line.truth.begin(), line.truth.end(), [](const auto& a, const auto& b) {
    return a.source.line < b.source.line;
  });
  if (first_truth != line.truth.end()) kind(first_truth->source.file, first_truth->position);
  Plane plane;
  if (line.projection) {
    try {
      plane.grid.emplace(*line.projection);
    } catch (Error& e) {
      throw InputError(e.message(), {{}, {}, "projection"});
    }
    notes.push_back("plane: " + geodesy::describe(*line.projection));
  } else if (first_geo_file && first_plane_file) {
    throw InputError(fmt::format("{} gives plane coordinates (x_m, y_m) and {} geographic ones (lat, lon): give a "
                                 "projection: to put both in one plane",
                                 *first_plane_file, *first_geo_file),
                     {{}, {}, "projection"});
  } else if (first_geo_file) {
    geodesy::GridDefinition g;
    g.system = geodesy::ZoneSystem::Custom;
    g.central_meridian_rad = std::round(*first_geo_lon / kDeg * 10.0) / 10.0 * kDeg;
    g.scale_factor = 1.0;
    g.false_easting_m = g.false_northing_m = 0.0;
    plane.grid.emplace(g);
    notes.push_back(fmt::format("plane: transverse Mercator on WGS84, central meridian {:.1f}° (the first "
                                "geographic position's longitude, {}, rounded to 0.1°), scale 1, false easting "
                                "and northing 0 (default: no projection: in the configuration)",
                                g.central_meridian_rad / kDeg, *first_geo_file));
  }
  return plane;
}

// Stations in the plane, the chains, and the LOPs with their time differences turned into
// range differences (their values are still ground lengths: lops_to_grid).
void stations_and_lops(const SurveyLine& line, const Plane& plane, Input& in, std::vector<std::string>& notes) {
  for (std::size_t k = 0; k < line.stations.size(); ++k) {
    const geodesy::GridPoint g = plane.forward(line.stations[k].position, at("stations", k, "position"));
    in.stations.push_back({line.stations[k].name, g.x_north_m, g.y_east_m});
  }
  for (const LineChain& c : line.chains) in.chains.push_back(c.chain);
  std::set<double> speeds_used;
  for (const LopRecord& r : line.lops) {
    Lop l;
    l.time_s = r.time_s;
    l.type = r.kind == LopKind::Range ? LopType::Range : LopType::RangeDifference;
    l.station = r.station;
    l.station2 = r.station2;
    l.chain = r.chain;
    l.value_m = r.value_m;
    if (r.kind == LopKind::TimeDifference) {
      const double speed =
          r.chain == Lop::kNoChain ? kLoranPropagationSpeed_m_s : line.chains.at(r.chain).propagation_speed_m_s;
      l.value_m = speed * r.time_difference_us * 1e-6;
      speeds_used.insert(speed);
    }
    l.sigma_m = r.sigma_m;
    in.lops.push_back(l);
  }
  if (!speeds_used.empty()) {
    std::string list;
    for (double v : speeds_used) list += (list.empty() ? "" : ", ") + fmt::format("{} m/s", v);
    notes.push_back(fmt::format("time differences (µs) converted to range differences with the propagation "
                                "speed {} (LORAN-C default {} m/s; a chain's propagation_speed_m_s overrides it); "
                                "no additional secondary factor is applied",
                                list, kLoranPropagationSpeed_m_s));
  }
}

// Fixes and truth in the plane: a geographic σ north/east rotated by −γ and scaled by k.
void fixes_and_truth(const SurveyLine& line, const Plane& plane, Input& in) {
  for (std::size_t k = 0; k < line.fixes.size(); ++k) {
    const FixRecord& r = line.fixes[k];
    const geodesy::GridPoint g = plane.forward(r.position, at("fixes", k, "position"));
    Fix f;
    f.time_s = r.time_s;
    f.x_north_m = g.x_north_m, f.y_east_m = g.y_east_m;
    const Eigen::Vector2d var(r.sigma_north_m * r.sigma_north_m, r.sigma_east_m * r.sigma_east_m);
    if (r.position.geographic) {
      const Eigen::Matrix2d m = to_grid(g.convergence_rad, g.scale);
      f.covariance = m * var.asDiagonal() * m.transpose();
      f.covariance = 0.5 * (f.covariance + f.covariance.transpose()).eval();
    } else {
      f.covariance = var.asDiagonal();
    }
    in.fixes.push_back(f);
  }
  for (std::size_t k = 0; k < line.truth.size(); ++k) {
    const TruthRecord& r = line.truth[k];
    const geodesy::GridPoint g = plane.forward(r.position, at("truth", k, "position"));
    in.truth.push_back({r.time_s, g.x_north_m, g.y_east_m});
  }
}

// The initial position: the line's, else the fix nearest the first DR epoch (within
// kInitialFixWindow_s), which nav::process moves by the DR to that epoch.
void initial_position(const SurveyLine& line, const Plane& plane, Input& in, std::vector<std::string>& notes) {
  const double t0 = line.dr.front().time_s;
  if (line.initial) {
    const geodesy::GridPoint g = plane.forward(*line.initial, "initial");
    in.initial.x_north_m = g.x_north_m, in.initial.y_east_m = g.y_east_m;
    if (line.initial_sigma_m)
      in.initial.sigma_m = *line.initial_sigma_m;
    else
      notes.push_back(fmt::format("initial position: sigma {} m per coordinate (default; set initial.sigma_m)",
                                  in.initial.sigma_m));
    return;
  }
  std::optional<std::size_t> best;
  for (std::size_t k = 0; k < in.fixes.size(); ++k)
    if (std::abs(in.fixes[k].time_s - t0) <= kInitialFixWindow_s &&
        (!best || std::abs(in.fixes[k].time_s - t0) < std::abs(in.fixes[*best].time_s - t0)))
      best = k;
  if (!best)
    throw InputError(fmt::format("no fix within {} s of the first DR epoch (t = {} s, {} line {}): give initial: "
                                 "{{x_m, y_m, sigma_m}} or {{lat, lon, sigma_m}}",
                                 kInitialFixWindow_s, t0, line.dr.front().source.file, line.dr.front().source.line),
                     {{}, {}, "initial"});
  const Fix& f = in.fixes[*best];
  // nav::process moves it by the DR to the first epoch; here it only starts the walk of the
  // grid convergence along the DR.
  in.initial_fix = *best;
  in.initial.x_north_m = f.x_north_m, in.initial.y_east_m = f.y_east_m;
  const SourceLine& s = line.fixes[*best].source;
  notes.push_back(fmt::format("initial position: the fix of {} line {} (t = {:.3f} s, sigma {:.3g} m) moved by the "
                              "dead reckoning to the first DR epoch (t = {:.3f} s), its covariance grown by the DR's "
                              "over those {:.3f} s; that fix is not used again as an observation (default: no "
                              "initial: in the configuration)",
                              s.file, s.line, f.time_s, std::sqrt(std::max(f.covariance(0, 0), f.covariance(1, 1))),
                              t0, std::abs(f.time_s - t0)));
}

// The σ of the DR samples, with a note for each default used.
struct DrSigmas {
  double speed_m_s, heading_rad, velocity_m_s;
};
DrSigmas dr_sigmas(const SurveyLine& line, std::vector<std::string>& notes) {
  const DrSigmas s{line.sigma_speed_m_s.value_or(kDefaultSigmaSpeed_m_s),
                   line.sigma_heading_rad.value_or(kDefaultSigmaHeading_deg * kDeg),
                   line.sigma_velocity_m_s.value_or(kDefaultSigmaSpeed_m_s)};
  if (line.dr_kind == DrKind::SpeedHeading) {
    if (!line.sigma_speed_m_s)
      notes.push_back(fmt::format("DR speed sigma {} m/s (default; set sigma_speed_m_s)", s.speed_m_s));
    if (!line.sigma_heading_rad)
      notes.push_back(fmt::format("DR heading sigma {}° (default; set sigma_heading_deg)", kDefaultSigmaHeading_deg));
  } else if (!line.sigma_velocity_m_s) {
    notes.push_back(
        fmt::format("DR velocity sigma {} m/s per component (default; set sigma_velocity_m_s)", s.velocity_m_s));
  }
  return s;
}

/// A dead-reckoned position (t, x, y).
using TrackPosition = std::array<double, 3>;

// Dead reckoning in the plane: with a grid, true headings and velocities turned by −γ and scaled
// by k at the dead-reckoned position. Returns the dead-reckoned track (for lops_to_grid).
std::vector<TrackPosition> dead_reckon(const SurveyLine& line, const Plane& plane, Input& in,
                                       std::vector<std::string>& notes) {
  const DrSigmas sigma = dr_sigmas(line, notes);
  if (plane.grid)
    notes.push_back("DR: true headings and velocities turned into the grid (T = alpha - gamma, speed times the point "
                    "scale k) along the dead-reckoned track");
  const bool speed_heading = line.dr_kind == DrKind::SpeedHeading;
  double x = in.initial.x_north_m, y = in.initial.y_east_m;
  std::vector<TrackPosition> track;
  track.reserve(line.dr.size());
  for (std::size_t k = 0; k < line.dr.size(); ++k) {
    const DrRecord& r = line.dr[k];
    const std::string field = at("dr", k, speed_heading ? "heading_rad" : "v_north_m_s");
    double gamma = 0.0, scale = 1.0;
    if (plane.grid) {
      try {
        const geodesy::GeographicPoint q = plane.grid->reverse(x, y);
        gamma = q.convergence_rad, scale = q.scale;
      } catch (Error& e) {
        throw InputError(fmt::format("the dead-reckoned position ({:.1f}, {:.1f}) m leaves the projection: {}", x, y,
                                     e.message()),
                         {{}, {}, field});
      }
    }
    DrSample s;
    if (speed_heading) {
      try {
        s = dr_from_speed_heading(r.time_s, r.speed_m_s * scale, r.heading_rad - gamma, sigma.speed_m_s * scale,
                                  sigma.heading_rad);
      } catch (Error& e) {
        e.add_context({}, std::nullopt, at("dr", k, ""));
        throw;
      }
    } else {
      s.time_s = r.time_s;
      const Eigen::Vector2d v = to_grid(gamma, scale) * Eigen::Vector2d(r.v_north_m_s, r.v_east_m_s);
      s.v_north_m_s = v.x(), s.v_east_m_s = v.y();
      s.covariance = Eigen::Matrix2d::Identity() * (sigma.velocity_m_s * sigma.velocity_m_s * scale * scale);
    }
    if (k > 0) {
      const Eigen::Vector2d d = detail::dr_increment(s, r.time_s - line.dr[k - 1].time_s, 0.0).delta;
      x += d.x(), y += d.y();
    }
    in.dr.push_back(s);
    track.push_back({r.time_s, x, y});
  }
  return track;
}

// The dead-reckoned ship at time t (linear between the track's epochs, held beyond them).
std::array<double, 2> ship_at(const std::vector<TrackPosition>& track, double t) {
  const auto it = std::lower_bound(track.begin(), track.end(), t,
                                   [](const TrackPosition& p, double tt) { return p[0] < tt; });
  if (it == track.begin()) return {(*it)[1], (*it)[2]};
  if (it == track.end()) return {track.back()[1], track.back()[2]};
  const TrackPosition& a = *std::prev(it);
  const TrackPosition& b = *it;
  const double w = (t - a[0]) / (b[0] - a[0]);
  return {a[1] + w * (b[1] - a[1]), a[2] + w * (b[2] - a[2])};
}

// With a grid, LOPs measured on the ground become grid lengths: each distance d of the ship to
// a station times the line scale factor k_line = (k_ship + 4·k_mid + k_station)/6 (Simpson's
// rule along the chord), the ship at its dead-reckoned position at the LOP's time.
void lops_to_grid(const Plane& plane, const std::vector<TrackPosition>& track, Input& in,
                  std::vector<std::string>& notes) {
  if (!plane.grid || in.lops.empty()) return;
  const auto scale_at = [&](double px, double py) { return plane.grid->reverse(px, py).scale; };
  double max_ppm = 0.0;
  for (std::size_t k = 0; k < in.lops.size(); ++k) {
    Lop& l = in.lops[k];
    const std::array<double, 2> p = ship_at(track, l.time_s);
    // k_line of one station, and (k_line − 1)·d/k_line: the grid length minus the ground length.
    const auto excess = [&](std::size_t si) {
      const Station& st = in.stations[si];
      const double kl = (scale_at(p[0], p[1]) + 4.0 * scale_at(0.5 * (p[0] + st.x_north_m), 0.5 * (p[1] + st.y_east_m)) +
                         scale_at(st.x_north_m, st.y_east_m)) / 6.0;
      max_ppm = std::max(max_ppm, std::abs(kl - 1.0) * 1e6);
      return std::pair{kl, (kl - 1.0) * std::hypot(p[0] - st.x_north_m, p[1] - st.y_east_m) / kl};
    };
    try {
      if (l.type == LopType::Range) {
        const double kl = excess(l.station).first;
        l.value_m *= kl;
        l.sigma_m *= kl;
      } else {
        const auto [k1, e1] = excess(l.station);
        const auto [k2, e2] = excess(l.station2);
        l.value_m += e1 - e2;
        l.sigma_m *= 0.5 * (k1 + k2);
      }
    } catch (Error& e) {
      throw InputError("the dead-reckoned position at this LOP leaves the projection: " + e.message(),
                       {{}, {}, at("lops", k, "")});
    }
  }
  notes.push_back(fmt::format("LOPs reduced from ground to grid lengths with the line scale factor (Simpson's rule "
                              "over k at the ship's dead-reckoned position, the midpoint and the station; up to "
                              "{:.1f} ppm here)",
                              max_ppm));
}

// "lops.csv:14" of a record read from a file; empty for one made by a program.
std::string source_text(const SourceLine& s) {
  if (s.file.empty()) return {};
  return fmt::format("{}:{}", std::filesystem::path(s.file).filename().string(), s.line);
}

}  // namespace

PlaneLine to_plane(const SurveyLine& line) {
  if (line.dr.size() < 2)
    throw InputError(fmt::format("{} DR sample{}: a line needs at least 2", line.dr.size(),
                                 line.dr.size() == 1 ? "" : "s"),
                     {{}, {}, "dr"});
  PlaneLine out;
  const Plane plane = choose_plane(line, out.notes);
  if (plane.grid) out.projection = plane.grid->definition();
  Input& in = out.input;
  in.options = line.options;
  stations_and_lops(line, plane, in, out.notes);
  fixes_and_truth(line, plane, in);
  initial_position(line, plane, in, out.notes);
  const std::vector<TrackPosition> track = dead_reckon(line, plane, in, out.notes);
  lops_to_grid(plane, track, in, out.notes);
  return out;
}

Result process(const SurveyLine& line, Progress* progress) {
  PlaneLine plane = to_plane(line);
  Result r;
  try {
    r = process(plane.input, progress);
  } catch (...) {
    if (progress) progress->finish();
    throw;
  }
  r.projection = std::move(plane.projection);
  const auto source = [&](RejectedObservation::Kind kind, std::size_t index) {
    if (kind == RejectedObservation::Kind::Lop) return index < line.lops.size() ? source_text(line.lops[index].source) : "";
    return index < line.fixes.size() ? source_text(line.fixes[index].source) : std::string();
  };
  for (RejectedObservation& o : r.rejected) o.source = source(o.kind, o.index);
  for (SkippedObservation& o : r.skipped) o.source = source(o.kind, o.index);
  r.notes.insert(r.notes.end(), line.notes.begin(), line.notes.end());
  r.notes.insert(r.notes.end(), plane.notes.begin(), plane.notes.end());
  r.warnings.insert(r.warnings.end(), line.warnings.begin(), line.warnings.end());
  return r;
}

}  // namespace meridian::nav
