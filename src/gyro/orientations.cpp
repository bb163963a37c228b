#include "meridian/gyro/orientations.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "meridian/core/angle.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/unicode.hpp"
#include "meridian/core/units.hpp"

namespace meridian::gyro {

bool OrientationsResult::all_checks_pass() const {
  return std::all_of(checks.begin(), checks.end(), [](const Check& c) { return c.pass; });
}

double point_distance_m(const PointResult& a, const PointResult& b) {
  // Two points a few metres apart at most matter: a sphere of the mean radius is exact to 0.5 %.
  constexpr double kRadius_m = 6371000.0;
  const double dn = (b.lat_rad - a.lat_rad) * kRadius_m;
  const double de = wrap_signed_rad(b.lon_rad - a.lon_rad) * std::cos(0.5 * (a.lat_rad + b.lat_rad)) * kRadius_m;
  return std::hypot(dn, de);
}

std::string to_string(ErrorSource::Kind kind) {
  switch (kind) {
    case ErrorSource::Kind::KnownAzimuth:
      return "known line azimuth";
    case ErrorSource::Kind::Eta:
      return "eta";
    case ErrorSource::Kind::Xi:
      return "xi";
    case ErrorSource::Kind::InstrumentConstant:
      return "instrument constant";
  }
  throw InputError(fmt::format("unknown error source kind {}", static_cast<int>(kind)));
}

namespace {

// Every run of a campaign with its field path.
std::vector<std::pair<const DeterminationInput*, std::string>> runs_of(const CampaignInput& c) {
  std::vector<std::pair<const DeterminationInput*, std::string>> v;
  const auto add = [&](const std::vector<DeterminationInput>& runs, const char* what) {
    for (std::size_t i = 0; i < runs.size(); ++i) v.emplace_back(&runs[i], fmt::format("{}[{}]", what, i));
  };
  if (c.known_line) {
    add(c.known_line->before, "known_line.before");
    add(c.known_line->after, "known_line.after");
  }
  add(c.line.determinations, "line.determinations");
  return v;
}

// Values booked to 0.001″ and a smooth model 5 cm apart agree far better than this.
constexpr double kSameValue_rad = 0.001 * units::kArcsecond;

bool near_points(double lat1, double lon1, double lat2, double lon2) {
  PointResult a, b;
  a.lat_rad = lat1, a.lon_rad = lon1, b.lat_rad = lat2, b.lon_rad = lon2;
  return point_distance_m(a, b) <= kSamePointTolerance_m;
}

}  // namespace

bool same_error_source(const ErrorSource& a, const ErrorSource& b) {
  if (a.kind != b.kind || a.source != b.source) return false;
  if (std::abs(wrap_signed_rad(a.value_rad - b.value_rad)) > kSameValue_rad) return false;
  if (a.kind == ErrorSource::Kind::InstrumentConstant) return std::abs(a.contribution_rad) == std::abs(b.contribution_rad);
  if (!near_points(a.lat_rad, a.lon_rad, b.lat_rad, b.lon_rad)) return false;
  if (a.to_lat_rad && b.to_lat_rad && !near_points(*a.to_lat_rad, *a.to_lon_rad, *b.to_lat_rad, *b.to_lon_rad))
    return false;
  return true;
}

double shared_covariance_rad2(const CampaignResult& a, const CampaignResult& b) {
  double c = 0;
  for (const ErrorSource& x : a.shared_error_sources)
    for (const ErrorSource& y : b.shared_error_sources)
      if (same_error_source(x, y)) c += x.contribution_rad * y.contribution_rad;
  return c;
}

namespace {

// The covariance of the orientations' T through their shared error sources, and the σ of the mean
// (error_sources.hpp): own parts bounded below by the scatter, shared parts added (the scatter
// cannot see them: they cancel in T_i − T_j).
void correlate(const std::vector<CampaignResult>& in, OrientationsResult& r) {
  const std::size_t n = in.size();
  const double nn = static_cast<double>(n) * static_cast<double>(n);
  r.covariance_rad2.assign(n, std::vector<double>(n, 0.0));
  double total = 0, own = 0, independent = 0;
  std::vector<const ErrorSource*> listed;
  for (std::size_t i = 0; i < n; ++i) {
    const double si = in[i].chain.grid_azimuth_rad.sigma;
    independent += si * si;
    double shared_i = 0;  // Σ c² of i's sources that another orientation shares
    for (const ErrorSource& x : in[i].shared_error_sources) {
      bool shared = false;
      for (std::size_t j = 0; j < n && !shared; ++j)
        if (j != i)
          for (const ErrorSource& y : in[j].shared_error_sources) shared = shared || same_error_source(x, y);
      if (!shared) continue;
      shared_i += x.contribution_rad * x.contribution_rad;
      // One source under two spellings of its point's name ("Ⅱ3", "Ⅱ３") is listed once.
      if (std::any_of(listed.begin(), listed.end(), [&](const ErrorSource* l) { return same_error_source(*l, x); }))
        continue;
      listed.push_back(&x);
      const std::string what = x.point.empty() ? fmt::format("{} ({})", to_string(x.kind), x.source)
                                               : fmt::format("{} at {} ({})", to_string(x.kind), x.point, x.source);
      if (std::find(r.shared_sources.begin(), r.shared_sources.end(), what) == r.shared_sources.end())
        r.shared_sources.push_back(what);
    }
    own += std::max(0.0, si * si - shared_i);
    for (std::size_t j = 0; j < n; ++j) r.covariance_rad2[i][j] = i == j ? si * si : shared_covariance_rad2(in[i], in[j]);
  }
  for (const auto& row : r.covariance_rad2)
    for (double c : row) total += c;
  const double shared = std::max(0.0, total - own);
  r.sigma_if_independent_rad = std::sqrt(independent / nn);
  r.sigma_own_propagated_rad = std::sqrt(own / nn);
  r.sigma_shared_rad = std::sqrt(shared / nn);
  r.mean.sigma_propagated = std::sqrt(total / nn);
  const double floor = std::isfinite(r.mean.sigma_empirical) ? std::max(r.sigma_own_propagated_rad, r.mean.sigma_empirical)
                                                             : r.sigma_own_propagated_rad;
  r.mean.mean.sigma = std::hypot(floor, r.sigma_shared_rad);
}

}  // namespace

OrientationsResult combine_orientations(const std::vector<CampaignResult>& in) {
  if (in.size() < 2)
    throw InputError(fmt::format("two or more independent orientations are needed, got {}", in.size()),
                     {"", std::nullopt, "orientations"});
  OrientationsResult r;
  // The tightest limits of the orientations (their classes or files may differ).
  RegulationLimits limits = in.front().limits;
  for (const CampaignResult& c : in) {
    if (c.limits.orientation_difference_rad < limits.orientation_difference_rad) {
      limits.orientation_difference_rad = c.limits.orientation_difference_rad;
      limits.source = c.limits.source;
    }
    limits.orientation_mean_sigma_rad = std::min(limits.orientation_mean_sigma_rad, c.limits.orientation_mean_sigma_rad);
  }
  r.limits = limits;
  for (const CampaignResult& c : in) r.files.push_back(c.input.file);
  r.station = in.front().station.name;
  r.target = in.front().target ? in.front().target->name : std::string();
  for (std::size_t i = 0; i < in.size(); ++i) {
    const CampaignResult& c = in[i];
    const std::string field = fmt::format("orientations[{}]", i);
    // The same line is the same points: by their coordinates (names may be written differently,
    // "Ⅱ3" and a full-width "Ⅱ３"; a point moved keeps its name), by name where one has none.
    const auto same_point = [&](const PointResult& p, const PointResult& q, const char* role) {
      const double d = point_distance_m(p, q);
      if (d > kSamePointTolerance_m)
        throw InputError(fmt::format("orientation {}: its {} {} is {:.3f} m from the {} {} of orientation 1 (limit "
                                     "{:.2f} m): not the same line",
                                     i + 1, role, p.name, d, role, q.name, kSamePointTolerance_m),
                         {"", std::nullopt, field});
      if (!same_name_nfkc(p.name, q.name) && i > 0)
        r.notes.push_back(fmt::format("orientation {}: its {} is named {} and {} in orientation 1; the same point by its "
                                      "coordinates ({:.3f} m apart)",
                                      i + 1, role, p.name, q.name, d));
    };
    same_point(c.station, in.front().station, "station");
    if (c.target && in.front().target) {
      same_point(*c.target, *in.front().target, "target");
    } else {
      const std::string target = c.target ? c.target->name : std::string();
      if (target.empty() != r.target.empty())
        throw InputError(fmt::format("orientation {} {}: that it is the same line cannot be shown; give line.to in "
                                     "every file",
                                     target.empty() ? i + 1 : 1,
                                     "names no target (line.to) while the other gives one"),
                         {"", std::nullopt, field});
      if (!same_name_nfkc(target, r.target))
        throw InputError(fmt::format("orientation {} is of the line {}-{}, not {}-{}", i + 1, c.station.name, target,
                                     r.station, r.target),
                         {"", std::nullopt, field});
    }
    r.grid_azimuths_rad.push_back(c.chain.grid_azimuth_rad);
  }
  for (std::size_t i = 0; i < in.size(); ++i) {
    int failed = 0;
    for (const auto& k : in[i].checks) failed += k.pass ? 0 : 1;
    r.checks.push_back({fmt::format("orientation {}: failed checks of its own", i + 1), static_cast<double>(failed),
                        0.0, CheckUnit::Checks, failed == 0, false, false,
                        "every orientation must pass its own checks", fmt::format("orientations[{}]", i)});
  }
  r.mean = mean_direction(r.grid_azimuths_rad);
  correlate(in, r);
  r.checks.push_back({"independent orientations, largest difference of the grid azimuths",
                      r.mean.max_difference / units::kArcsecond, limits.orientation_difference_rad / units::kArcsecond,
                      CheckUnit::Arcsec, r.mean.max_difference <= limits.orientation_difference_rad, false, false,
                      limits.source, ""});
  r.checks.push_back({"independent orientations, sigma of the mean", r.mean.mean.sigma / units::kArcsecond,
                      limits.orientation_mean_sigma_rad / units::kArcsecond, CheckUnit::Arcsec,
                      r.mean.mean.sigma <= limits.orientation_mean_sigma_rad, false, false, limits.source, ""});
  // Independent orientations have runs of their own: a run whose gyro observations are another
  // orientation's (a copied book with a face reading retyped, or the same calibration runs reused)
  // makes them one orientation, and a shared E would be counted as independent.
  for (std::size_t j = 1; j < in.size(); ++j) {
    std::vector<std::string> shared;
    for (std::size_t i = 0; i < j; ++i)
      for (const auto& [x, xname] : runs_of(in[j].input))
        for (const auto& [y, yname] : runs_of(in[i].input))
          if (same_observations(*x, *y)) shared.push_back(fmt::format("{} = orientation {}'s {}", xname, i + 1, yname));
    r.checks.push_back({fmt::format("orientation {}: no run of another orientation{}", j + 1,
                                    shared.empty() ? "" : fmt::format(" ({})", fmt::join(shared, "; "))),
                        static_cast<double>(shared.size()), 0.0, CheckUnit::Runs, shared.empty(), false, false,
                        "independent orientations: each its own calibration and runs (spec 7.1)",
                        fmt::format("orientations[{}]", j)});
  }
  if (r.sigma_shared_rad > 0)
    r.notes.push_back(fmt::format(
        "sigma of the mean {:.2f}\" = sqrt(max(own propagated {:.2f}\", empirical {:.2f}\")^2 + shared {:.2f}\"^2); "
        "shared by the orientations: {} (correlated; as if independent it would be {:.2f}\")",
        r.mean.mean.sigma / units::kArcsecond, r.sigma_own_propagated_rad / units::kArcsecond,
        r.mean.sigma_empirical / units::kArcsecond, r.sigma_shared_rad / units::kArcsecond,
        fmt::join(r.shared_sources, ", "), r.sigma_if_independent_rad / units::kArcsecond));
  else
    r.notes.push_back(fmt::format("sigma of the mean: the larger of propagated {:.2f}\" and empirical {:.2f}\" "
                                  "(no error source shared by the orientations)",
                                  r.mean.sigma_propagated / units::kArcsecond,
                                  r.mean.sigma_empirical / units::kArcsecond));
  return r;
}

}  // namespace meridian::gyro
