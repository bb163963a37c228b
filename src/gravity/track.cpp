#include "meridian/gravity/track.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

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

}  // namespace

TrackResult evaluate_track(const GravityField& field, std::span<const GeodeticPoint> track, Quantities what,
                           const TrackOptions& o) {
  if (!(o.tolerance_rad > 0) || !(o.tolerance_geoid_m > 0) || !(o.max_node_spacing_m >= 0))
    throw InputError("track tolerances must be positive", {"", {}, "tolerance"});
  for (std::size_t i = 0; i < track.size(); ++i) {
    try {
      GravityField::check_point(track[i]);
    } catch (Error& e) {
      e.add_context("", std::nullopt, fmt::format("track[{}]", i));
      throw;
    }
  }
  TrackResult res;
  const std::size_t n = track.size();
  res.values.resize(n);
  if (n == 0) return res;
  // Along-track distance (chords between consecutive ECEF positions).
  std::vector<double> s(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) {
    const EcefPosition a = field.normal().to_ecef(track[i - 1].lat_rad, track[i - 1].lon_rad, track[i - 1].height_m);
    const EcefPosition b = field.normal().to_ecef(track[i].lat_rad, track[i].lon_rad, track[i].height_m);
    s[i] = s[i - 1] + std::hypot(std::hypot(b.x_m - a.x_m, b.y_m - a.y_m), b.z_m - a.z_m);
  }
  const double spacing =
      o.max_node_spacing_m > 0 ? o.max_node_spacing_m : 0.05 * 6371000.0 / std::max(1, field.max_degree());
  // Initial nodes: first, last, and the first point past each multiple of the spacing.
  std::vector<std::size_t> nodes{0};
  for (std::size_t i = 1; i + 1 < n; ++i)
    if (s[i] - s[nodes.back()] >= spacing || s[i + 1] - s[nodes.back()] > spacing) nodes.push_back(i);
  if (n > 1) nodes.push_back(n - 1);
  std::vector<char> known(n, 0);
  auto evaluate = [&](const std::vector<std::size_t>& idx) {
    std::vector<GeodeticPoint> pts;
    pts.reserve(idx.size());
    for (std::size_t i : idx) pts.push_back(track[i]);
    const std::vector<FieldValues> v = field.evaluate(pts, what);
    for (std::size_t k = 0; k < idx.size(); ++k) {
      res.values[idx[k]] = v[k];
      known[idx[k]] = 1;
    }
    res.model_evaluations += idx.size();
  };
  evaluate(nodes);
  // Intervals [i, j] between evaluated points still to be checked.
  std::vector<std::pair<std::size_t, std::size_t>> open, next;
  for (std::size_t k = 0; k + 1 < nodes.size(); ++k)
    if (nodes[k + 1] > nodes[k] + 1) open.emplace_back(nodes[k], nodes[k + 1]);
  const bool defl = includes(what, Quantities::Deflection),
             geoid = includes(what, Quantities::Geoid);
  while (!open.empty()) {
    std::vector<std::size_t> mids;
    for (const auto& [i, j] : open) {
      // The point nearest the middle in distance.
      const double sm = 0.5 * (s[i] + s[j]);
      std::size_t k = static_cast<std::size_t>(std::lower_bound(s.begin() + static_cast<std::ptrdiff_t>(i) + 1,
                                                                s.begin() + static_cast<std::ptrdiff_t>(j), sm) -
                                               s.begin());
      if (k > i + 1 && sm - s[k - 1] < s[k] - sm) --k;
      k = std::clamp(k, i + 1, j - 1);
      mids.push_back(k);
    }
    evaluate(mids);
    next.clear();
    for (std::size_t q = 0; q < open.size(); ++q) {
      const auto [i, j] = open[q];
      const std::size_t k = mids[q];
      const double w = s[j] > s[i] ? (s[k] - s[i]) / (s[j] - s[i]) : 0.5;
      const FieldValues li = lerp(res.values[i], res.values[j], w), &v = res.values[k];
      double ed = 0, eg = 0;
      if (defl)
        ed = std::max({std::abs(li.xi_rad - v.xi_rad), std::abs(li.eta_rad - v.eta_rad),
                       std::abs(li.xi_astro_rad - v.xi_astro_rad), std::abs(li.eta_astro_rad - v.eta_astro_rad)});
      if (geoid) eg = std::abs(li.geoid_m - v.geoid_m);
      if (ed > o.tolerance_rad || eg > o.tolerance_geoid_m) {
        if (k > i + 1) next.emplace_back(i, k);
        if (j > k + 1) next.emplace_back(k, j);
      } else {
        res.max_checked_error_rad = std::max(res.max_checked_error_rad, ed);
        res.max_checked_error_geoid_m = std::max(res.max_checked_error_geoid_m, eg);
        // Accept: interpolate the rest of [i, j] through i, k, j.
        for (std::size_t p = i + 1; p < j; ++p) {
          if (known[p]) continue;
          const std::size_t a = p < k ? i : k, b = p < k ? k : j;
          res.values[p] = lerp(res.values[a], res.values[b], s[b] > s[a] ? (s[p] - s[a]) / (s[b] - s[a]) : 0.5);
        }
      }
    }
    open.swap(next);
  }
  return res;
}

}  // namespace meridian::gravity
