#include "meridian/gravity/track.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::gravity {
namespace {

// The numeric members of FieldValues, for interpolation.
constexpr std::size_t kFields = 11;
static_assert(sizeof(FieldValues) == kFields * sizeof(double));

void as_array(const FieldValues& v, double* a) { std::memcpy(a, &v, sizeof v); }

FieldValues lerp(const FieldValues& a, const FieldValues& b, double w) {
  double x[kFields], y[kFields];
  as_array(a, x);
  as_array(b, y);
  for (std::size_t k = 0; k < kFields; ++k) x[k] += w * (y[k] - x[k]);
  FieldValues r;
  std::memcpy(&r, x, sizeof r);
  return r;
}

// Every point valid, as GravityField::evaluate checks them (field "track[i]").
void check_track(std::span<const GeodeticPoint> track) {
  for (std::size_t i = 0; i < track.size(); ++i) {
    try {
      GravityField::check_point(track[i]);
    } catch (Error& e) {
      e.add_context("", std::nullopt, fmt::format("track[{}]", i));
      throw;
    }
  }
}

// Along-track distance (chords between consecutive ECEF positions), s[0] = 0.
std::vector<double> along_track_distance(const GravityField& field, std::span<const GeodeticPoint> track) {
  const std::size_t n = track.size();
  std::vector<double> s(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) {
    const EcefPosition a = field.normal().to_ecef(track[i - 1].lat_rad, track[i - 1].lon_rad, track[i - 1].height_m);
    const EcefPosition b = field.normal().to_ecef(track[i].lat_rad, track[i].lon_rad, track[i].height_m);
    s[i] = s[i - 1] + std::hypot(std::hypot(b.x_m - a.x_m, b.y_m - a.y_m), b.z_m - a.z_m);
  }
  return s;
}

// Initial nodes: first, last, and the first point past each multiple of the spacing.
std::vector<std::size_t> initial_nodes(const std::vector<double>& s, double spacing) {
  const std::size_t n = s.size();
  std::vector<std::size_t> nodes{0};
  for (std::size_t i = 1; i + 1 < n; ++i)
    if (s[i] - s[nodes.back()] >= spacing || s[i + 1] - s[nodes.back()] > spacing) nodes.push_back(i);
  if (n > 1) nodes.push_back(n - 1);
  return nodes;
}

// The adaptive refinement of one track: intervals [i, j] between evaluated points are checked
// at their midpoint k, then accepted (interpolated through i, k, j) or split at k.
class TrackRefinement {
 public:
  TrackRefinement(const GravityField& field, std::span<const GeodeticPoint> track, Quantities what,
                  const TrackOptions& o, std::vector<double> s)
      : field_(field), track_(track), what_(what), o_(o), s_(std::move(s)), known_(track.size(), 0),
        defl_(includes(what, Quantities::Deflection)), geoid_(includes(what, Quantities::Geoid)) {
    res_.values.resize(track.size());
  }

  TrackResult run(const std::vector<std::size_t>& nodes) {
    evaluate(nodes);
    std::vector<std::pair<std::size_t, std::size_t>> open, next;
    for (std::size_t k = 0; k + 1 < nodes.size(); ++k)
      if (nodes[k + 1] > nodes[k] + 1) open.emplace_back(nodes[k], nodes[k + 1]);
    while (!open.empty()) {
      std::vector<std::size_t> mids;
      for (const auto& [i, j] : open) mids.push_back(midpoint(i, j));
      evaluate(mids);
      next.clear();
      for (std::size_t q = 0; q < open.size(); ++q) check(open[q].first, mids[q], open[q].second, next);
      open.swap(next);
    }
    return std::move(res_);
  }

 private:
  // The model at the points `idx`, in one batch.
  void evaluate(const std::vector<std::size_t>& idx) {
    std::vector<GeodeticPoint> pts;
    pts.reserve(idx.size());
    for (std::size_t i : idx) pts.push_back(track_[i]);
    const std::vector<FieldValues> v = field_.evaluate(pts, what_);
    for (std::size_t k = 0; k < idx.size(); ++k) {
      res_.values[idx[k]] = v[k];
      known_[idx[k]] = 1;
    }
    res_.model_evaluations += idx.size();
  }

  // The point of (i, j) nearest the middle in distance.
  std::size_t midpoint(std::size_t i, std::size_t j) const {
    const double sm = 0.5 * (s_[i] + s_[j]);
    std::size_t k = static_cast<std::size_t>(std::lower_bound(s_.begin() + static_cast<std::ptrdiff_t>(i) + 1,
                                                              s_.begin() + static_cast<std::ptrdiff_t>(j), sm) -
                                             s_.begin());
    if (k > i + 1 && sm - s_[k - 1] < s_[k] - sm) --k;
    return std::clamp(k, i + 1, j - 1);
  }

  // Interpolation between i and j checked at k against the model: accept [i, j] (interpolate
  // the rest of it through i, k, j) or split it into [i, k] and [k, j] for the next round.
  void check(std::size_t i, std::size_t k, std::size_t j, std::vector<std::pair<std::size_t, std::size_t>>& next) {
    const double w = s_[j] > s_[i] ? (s_[k] - s_[i]) / (s_[j] - s_[i]) : 0.5;
    const FieldValues li = lerp(res_.values[i], res_.values[j], w), &v = res_.values[k];
    double ed = 0, eg = 0;
    if (defl_)
      ed = std::max({std::abs(li.xi_rad - v.xi_rad), std::abs(li.eta_rad - v.eta_rad),
                     std::abs(li.xi_astro_rad - v.xi_astro_rad), std::abs(li.eta_astro_rad - v.eta_astro_rad)});
    if (geoid_) eg = std::abs(li.geoid_m - v.geoid_m);
    if (ed > o_.tolerance_rad || eg > o_.tolerance_geoid_m) {
      if (k > i + 1) next.emplace_back(i, k);
      if (j > k + 1) next.emplace_back(k, j);
      return;
    }
    res_.max_checked_error_rad = std::max(res_.max_checked_error_rad, ed);
    res_.max_checked_error_geoid_m = std::max(res_.max_checked_error_geoid_m, eg);
    for (std::size_t p = i + 1; p < j; ++p) {
      if (known_[p]) continue;
      const std::size_t a = p < k ? i : k, b = p < k ? k : j;
      res_.values[p] = lerp(res_.values[a], res_.values[b], s_[b] > s_[a] ? (s_[p] - s_[a]) / (s_[b] - s_[a]) : 0.5);
    }
  }

  const GravityField& field_;
  std::span<const GeodeticPoint> track_;
  Quantities what_;
  const TrackOptions& o_;
  std::vector<double> s_;
  std::vector<char> known_;
  bool defl_, geoid_;
  TrackResult res_;
};

}  // namespace

TrackResult evaluate_track(const GravityField& field, std::span<const GeodeticPoint> track, Quantities what,
                           const TrackOptions& o) {
  if (!(o.tolerance_rad > 0) || !(o.tolerance_geoid_m > 0) || !(o.max_node_spacing_m >= 0))
    throw InputError("track tolerances must be positive", {"", {}, "tolerance"});
  check_track(track);
  if (track.empty()) return {};
  std::vector<double> s = along_track_distance(field, track);
  const double spacing =
      o.max_node_spacing_m > 0 ? o.max_node_spacing_m : 0.05 * 6371000.0 / std::max(1, field.max_degree());
  const std::vector<std::size_t> nodes = initial_nodes(s, spacing);
  return TrackRefinement(field, track, what, o, std::move(s)).run(nodes);
}

}  // namespace meridian::gravity
