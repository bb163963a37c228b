#pragma once
// Private to report_nav (not installed): what the navigation text, JSON, CSV and HTML writers
// share, so the unity batch of the target sees one definition.

#include <cmath>
#include <cstddef>
#include <string>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/nav/navigation.hpp"

namespace meridian::report::nav_detail {

inline const char* kind_name(nav::RejectedObservation::Kind k) {
  return k == nav::RejectedObservation::Kind::Lop ? "lop" : "fix";
}

/// Whether a method estimates the DR velocity bias (the others carry 0).
inline bool estimates_bias(nav::Method m) {
  return m != nav::Method::DeadReckoning && m != nav::Method::SequentialNoBias;
}

struct RejectionCounts {
  std::size_t lops = 0;
  std::size_t fixes = 0;
};

inline RejectionCounts rejection_counts(const nav::Result& r, nav::Method m) {
  RejectionCounts c;
  for (const auto& o : r.rejected)
    if (o.method == m) ++(o.kind == nav::RejectedObservation::Kind::Lop ? c.lops : c.fixes);
  return c;
}

/// The method's result, or InputError naming it and the methods the result holds.
inline const nav::MethodResult& require_method(const nav::Result& r, nav::Method m) {
  if (const nav::MethodResult* found = r.find(m)) return *found;
  std::string have;
  for (const auto& mr : r.methods) have += (have.empty() ? "" : ", ") + nav::to_string(mr.method);
  throw InputError(fmt::format("method \"{}\" is not in the navigation result (it holds: {})",
                               nav::to_string(m), have.empty() ? "no method" : have));
}

/// A σ as the writers state it: NaN (null, empty, "n/a") when not positive and finite.
inline double stated_sigma(double sigma) {
  return std::isfinite(sigma) && sigma > 0.0 ? sigma : std::nan("");
}

/// Index of the track point nearest in time to t (track times increase); track not empty.
inline std::size_t nearest_epoch(const std::vector<nav::TrackPoint>& track, double t) {
  std::size_t lo = 0, hi = track.size() - 1;
  while (hi - lo > 1) {
    const std::size_t mid = lo + (hi - lo) / 2;
    (track[mid].time_s <= t ? lo : hi) = mid;
  }
  return std::fabs(track[hi].time_s - t) < std::fabs(track[lo].time_s - t) ? hi : lo;
}

}  // namespace meridian::report::nav_detail
