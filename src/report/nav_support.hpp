#pragma once
// Private to report_nav (not installed): what the navigation text, JSON, CSV and HTML writers
// share, so the unity batch of the target sees one definition.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
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

/// The forward run whose accepted observations a method reuses (backward and fix-closure:
/// sequential-bias-I; rts: ekf); nullopt for a method that screens its own.
inline std::optional<nav::Method> observations_of(nav::Method m) {
  if (m == nav::Method::Backward || m == nav::Method::FixClosure) return nav::Method::SequentialBiasI;
  if (m == nav::Method::Rts) return nav::Method::Ekf;
  return std::nullopt;
}

/// The position σ of a track: the final σ_x, σ_y and the mean and max over the line of the
/// horizontal σ_h = √(σ_x² + σ_y²) (m); NaN for an empty track.
struct SigmaSummary {
  double final_x = std::nan(""), final_y = std::nan("");
  double mean_h = std::nan(""), max_h = std::nan("");
};
/// The status cell of a method: "consistent", or "diverged 36000.0–41400.0 s (fix-run, …)".
inline std::string nav_status_text(const nav::MethodResult& m) {
  const nav::Consistency& c = m.consistency;
  if (c.alarms.empty()) return nav::to_string(c.status);
  std::string t = nav::to_string(c.status);
  std::string checks;
  double from = c.alarms.front().from_s, to = c.alarms.front().to_s;
  for (const auto& a : c.alarms) {
    from = std::min(from, a.from_s);
    to = std::max(to, a.to_s);
    if (checks.find(a.check) == std::string::npos) checks += (checks.empty() ? "" : ", ") + a.check;
  }
  return t + " " + fmt::format("{:.1f}–{:.1f} s", from, to) + " (" + checks + ")";
}

/// A σ cell: the value, with "(not valid)" where the method's self-checks failed.
inline std::string nav_sigma_cell(const nav::MethodResult& m, const std::string& value) {
  return m.consistency.sigma_valid() ? value : value + " (not valid)";
}

inline SigmaSummary sigma_summary(const nav::MethodResult& m) {
  SigmaSummary s;
  if (m.track.empty()) return s;
  s.final_x = m.track.back().sigma_x_m();
  s.final_y = m.track.back().sigma_y_m();
  double sum = 0.0, mx = 0.0;
  for (const nav::TrackPoint& p : m.track) {
    const double h = std::sqrt(p.covariance(0, 0) + p.covariance(1, 1));
    sum += h;
    mx = std::max(mx, h);
  }
  s.mean_h = sum / static_cast<double>(m.track.size());
  s.max_h = mx;
  return s;
}

/// "chain \"Syledis\"" (its index when it has no name).
inline std::string chain_label(const nav::ChainParameter& p) {
  return p.chain_name.empty() ? fmt::format("chain {}", p.chain) : fmt::format("chain \"{}\"", p.chain_name);
}

/// "lops.csv:14" when the reader named it, else "LOP 12" / "fix 3" (0-based index).
inline std::string observation_label(nav::RejectedObservation::Kind k, std::size_t index,
                                     const std::string& source) {
  const char* kind = k == nav::RejectedObservation::Kind::Lop ? "LOP" : "fix";
  return source.empty() ? fmt::format("{} {}", kind, index) : fmt::format("{} {}", kind, source);
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
