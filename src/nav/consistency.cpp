// The self-checks of every method (spec §6a; docs/navigation.md, "Self-checks"): from the data
// alone — the fix misclosures against the combined σ, the share of rejected LOPs and the
// spread of the normalised LOP innovations in windows — a method that lost the observations is
// marked diverged, one whose residuals are wider than its σ inconsistent, with the stretch
// concerned; never silently.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "meridian/adjust/statistics.hpp"
#include "methods.hpp"

namespace meridian::nav {

std::string to_string(MethodStatus s) {
  switch (s) {
    case MethodStatus::Consistent: return "consistent";
    case MethodStatus::Inconsistent: return "inconsistent";
    case MethodStatus::Diverged: return "diverged";
  }
  return "consistent";
}

namespace detail {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMedianAbsNormal = 0.6744897501960817;  // median of |N(0, 1)|

// The method whose observations a derived method uses (it inherits their selection).
std::optional<Method> source_of(Method m) {
  if (m == Method::Backward || m == Method::FixClosure) return Method::SequentialBiasI;
  if (m == Method::Rts) return Method::Ekf;
  return std::nullopt;
}

bool forward(Method m) {
  return m == Method::SequentialNoBias || m == Method::SequentialBiasI ||
         m == Method::SequentialBiasII || m == Method::Ekf;
}

bool sequential_model(Method m) {
  return m == Method::SequentialNoBias || m == Method::SequentialBiasI ||
         m == Method::SequentialBiasII || m == Method::Backward || m == Method::FixClosure;
}

// The fixes compared with a method that has no innovations of its own (dead reckoning, the
// smoothers, the fix closure): the fix against the track at its epoch moved to the fix's time,
// normalised by the fix's σ + the track's (conservative where the method used the fix: its
// residual covariance is R − P, smaller).
std::vector<Monitor::FixTest> track_fix_tests(const Prepared& p, const Screening& sc, const MethodResult& m) {
  std::vector<Monitor::FixTest> out;
  for (const Reduced& red : p.fixes) {
    const TrackPoint& t = m.track[red.epoch];
    const Fix& f = p.input->fixes[red.index];
    const Eigen::Vector2d pos = Eigen::Vector2d(t.x_north_m, t.y_east_m) + red.delta +
                                red.dt_s * Eigen::Vector2d(t.bias_north_m_s, t.bias_east_m_s);
    const Eigen::Vector2d v = Eigen::Vector2d(f.x_north_m, f.y_east_m) - pos;
    const Eigen::Matrix2d C =
        t.covariance + f.covariance + (sequential_model(m.method) ? red.q_delta_seq : red.q_delta);
    const double chi2 = v.dot(C.ldlt().solve(v));
    out.push_back({red.index, red.epoch, chi2, v.norm(),
                   v.norm() > sc.fix_tolerance_m || chi2 > sc.fix_chi2_limit});
  }
  return out;
}

ConsistencyAlarm alarm(const Prepared& p, MethodStatus s, std::string check, std::size_t e0,
                       std::size_t e1, std::string reason) {
  ConsistencyAlarm a;
  a.status = s;
  a.check = std::move(check);
  a.from_epoch = e0;
  a.to_epoch = e1;
  a.from_s = p.t[e0];
  a.to_s = p.t[e1];
  a.reason = std::move(reason);
  return a;
}

// Runs of consecutive outlying fixes (kFixRunAlarm or more): diverged from the last fix that
// agreed (or the start) to the next one that agrees (or the end); and the spread of all the
// fixes' χ² against χ²_{1−α}(2K).
void fix_checks(const Prepared& p, const Screening& sc, double alpha, bool innovations,
                const std::vector<Monitor::FixTest>& fx, Consistency& c) {
  c.fixes_tested = fx.size();
  c.fix_sigma_ratio = kNaN;
  if (fx.empty()) return;
  double sum = 0.0;
  for (const auto& f : fx) {
    sum += f.chi2;
    c.fixes_outlying += f.outlying;
  }
  c.fix_sigma_ratio = std::sqrt(sum / (2.0 * static_cast<double>(fx.size())));
  const std::size_t last_epoch = p.epochs - 1;
  for (std::size_t i = 0; i < fx.size();) {
    if (!fx[i].outlying) {
      ++i;
      continue;
    }
    std::size_t j = i;
    double dmin = fx[i].distance_m, dmax = fx[i].distance_m, cmax = fx[i].chi2;
    while (j + 1 < fx.size() && fx[j + 1].outlying) {
      ++j;
      dmin = std::min(dmin, fx[j].distance_m);
      dmax = std::max(dmax, fx[j].distance_m);
      cmax = std::max(cmax, fx[j].chi2);
    }
    const std::size_t run = j - i + 1;
    c.longest_fix_run = std::max(c.longest_fix_run, run);
    if (run >= kFixRunAlarm) {
      const std::size_t e0 = i > 0 ? fx[i - 1].epoch : 0;
      const std::size_t e1 = j + 1 < fx.size() ? fx[j + 1].epoch : last_epoch;
      c.alarms.push_back(alarm(
          p, MethodStatus::Diverged, "fix-run", e0, e1,
          fmt::format("{} consecutive fixes (of {}) off the track: {:.1f} … {:.1f} m, χ²(2) up to {:.1f} "
                      "(limit {:.1f}, fix_tolerance_m {:g}); a run of disagreeing fixes means the track "
                      "is lost, not that the fixes are wrong",
                      run, fx.size(), dmin, dmax, cmax, sc.fix_chi2_limit, sc.fix_tolerance_m)));
    }
    i = j + 1;
  }
  // The spread of the fixes that agree (at least 3). A forward method's fix innovations are
  // (for a consistent filter) independent, so their Σχ² is χ²(2K) and is tested at α. The
  // misclosures of a track that did not predict them (dead reckoning, smoothers, the fix
  // closure) are correlated through the track's own error (its initial offset, its bias), so
  // their Σχ² is not χ²(2K) — a consistent dead reckoning failed that test in 1 of 10 clean
  // lines; for them the limit is on the mean χ², χ²_{1−α}(2) (what a single fix may reach),
  // valid even when the misclosures are fully correlated.
  std::size_t k = 0;
  double s_ok = 0.0;
  for (const auto& f : fx)
    if (!f.outlying) {
      s_ok += f.chi2;
      ++k;
    }
  if (k >= 3) {
    const double K = static_cast<double>(k);
    const double mean = s_ok / K;
    const double limit = innovations ? adjust::chi_squared_upper_quantile(alpha, 2.0 * K) : K * sc.fix_chi2_limit;
    if (s_ok > limit)
      c.alarms.push_back(alarm(
          p, MethodStatus::Inconsistent, "fix-spread", fx.front().epoch, fx.back().epoch,
          innovations
              ? fmt::format("the {} fix innovations that pass their test are wider than the method's σ: "
                            "Σχ² = {:.1f} > χ²_{{1−α}}({}) = {:.1f} (σ ratio {:.2f})",
                            k, s_ok, 2 * k, limit, std::sqrt(mean / 2.0))
              : fmt::format("the {} fixes that pass their test disagree with the track more than its σ "
                            "allow: mean χ²(2) = {:.1f} > {:.1f} (σ ratio {:.2f})",
                            k, mean, sc.fix_chi2_limit, std::sqrt(mean / 2.0))));
  }
}

// Windows of kConsistencyWindow_s every half window over the LOP innovations of a forward
// method: the share rejected (> kMaxRejectedShare: diverged) and the robust spread
// median|w|/0.6745 (> kMaxInnovationRatio: inconsistent); overlapping failing windows merge.
void lop_checks(const Prepared& p, const std::vector<Monitor::LopTest>& lops, Consistency& c) {
  c.lops_tested = lops.size();
  c.max_innovation_ratio = kNaN;
  for (const auto& l : lops) c.lops_rejected += l.rejected;
  if (lops.size() < kConsistencyMinLops) return;
  const double t0 = p.t.front();
  const double half = 0.5 * kConsistencyWindow_s;
  struct Open {
    bool on = false;
    std::size_t e0 = 0, e1 = 0;
    double worst = 0.0;
    std::size_t n = 0, rej = 0;
  };
  Open share, spread;
  const auto close = [&](Open& o, bool is_share) {
    if (!o.on) return;
    if (is_share)
      c.alarms.push_back(alarm(
          p, MethodStatus::Diverged, "rejected-share", o.e0, o.e1,
          fmt::format("up to {:.0f} % of the LOPs of a {:g} s window rejected (limit {:.0f} %; worst "
                      "window {} of {}): the track has drifted away from its observations",
                      100.0 * o.worst, kConsistencyWindow_s, 100.0 * kMaxRejectedShare, o.rej, o.n)));
    else
      c.alarms.push_back(alarm(
          p, MethodStatus::Inconsistent, "innovation-spread", o.e0, o.e1,
          fmt::format("the LOP innovations of a {:g} s window are {:.2f} times wider than their σ "
                      "(robust spread median|w|/0.6745, limit {:g})",
                      kConsistencyWindow_s, o.worst, kMaxInnovationRatio)));
    o = Open{};
  };
  std::vector<double> aw;
  std::size_t begin = 0;
  for (double ws = t0; ws <= p.t.back(); ws += half) {
    while (begin < lops.size() && p.t[lops[begin].epoch] < ws) ++begin;
    std::size_t end = begin;
    while (end < lops.size() && p.t[lops[end].epoch] < ws + kConsistencyWindow_s) ++end;
    const std::size_t n = end - begin;
    if (n < kConsistencyMinLops) {
      if (ws + kConsistencyWindow_s > p.t.back()) break;
      continue;
    }
    std::size_t rej = 0;
    aw.clear();
    for (std::size_t i = begin; i < end; ++i) {
      rej += lops[i].rejected;
      aw.push_back(std::abs(lops[i].w));
    }
    const auto mid = aw.begin() + static_cast<std::ptrdiff_t>(aw.size() / 2);
    std::nth_element(aw.begin(), mid, aw.end());
    const double ratio = *mid / kMedianAbsNormal;
    const double sh = static_cast<double>(rej) / static_cast<double>(n);
    c.max_rejected_share = std::max(c.max_rejected_share, sh);
    c.max_innovation_ratio = std::isfinite(c.max_innovation_ratio) ? std::max(c.max_innovation_ratio, ratio) : ratio;
    const std::size_t e0 = lops[begin].epoch, e1 = lops[end - 1].epoch;
    const auto extend = [&](Open& o, bool fail, double value) {
      if (!fail) return false;
      if (!o.on) {
        o.on = true;
        o.e0 = e0;
      }
      o.e1 = e1;
      if (value > o.worst) {
        o.worst = value;
        o.n = n;
        o.rej = rej;
      }
      return true;
    };
    if (!extend(share, sh > kMaxRejectedShare, sh)) close(share, true);
    if (!extend(spread, ratio > kMaxInnovationRatio, ratio)) close(spread, false);
    if (ws + kConsistencyWindow_s > p.t.back()) break;
  }
  close(share, true);
  close(spread, false);
}

MethodStatus worst(const std::vector<ConsistencyAlarm>& alarms) {
  MethodStatus s = MethodStatus::Consistent;
  for (const auto& a : alarms)
    if (static_cast<int>(a.status) > static_cast<int>(s)) s = a.status;
  return s;
}

}  // namespace

void check_consistency(const Prepared& p, const Screening& sc, const std::vector<Monitor>& monitors,
                       Result& res) {
  const double alpha = p.input->options.alpha;
  for (MethodResult& m : res.methods) {
    Consistency& c = m.consistency;
    c = Consistency{};
    const Monitor& mon = monitors[static_cast<std::size_t>(m.method)];
    if (forward(m.method)) {
      fix_checks(p, sc, alpha, true, mon.fixes, c);
      lop_checks(p, mon.lops, c);
    } else {
      fix_checks(p, sc, alpha, false, track_fix_tests(p, sc, m), c);
      c.max_innovation_ratio = kNaN;
    }
  }
  // A derived method uses its source's observations: the source's divergence is its own.
  for (MethodResult& m : res.methods) {
    const auto src = source_of(m.method);
    if (!src) continue;
    const MethodResult* s = res.find(*src);
    if (!s) continue;
    for (const ConsistencyAlarm& a : s->consistency.alarms) {
      if (a.status != MethodStatus::Diverged) continue;
      ConsistencyAlarm b = a;
      b.reason = fmt::format("inherited from {} (whose observations it uses): {}", to_string(*src), a.reason);
      m.consistency.alarms.push_back(std::move(b));
    }
  }
  for (MethodResult& m : res.methods) {
    Consistency& c = m.consistency;
    std::sort(c.alarms.begin(), c.alarms.end(),
              [](const ConsistencyAlarm& a, const ConsistencyAlarm& b) { return a.from_epoch < b.from_epoch; });
    c.status = worst(c.alarms);
    for (const ConsistencyAlarm& a : c.alarms)
      res.warnings.push_back(fmt::format("{} {} from {:.1f} s to {:.1f} s (epochs {}–{}), check {}: {}; its σ are "
                                         "not valid there",
                                         to_string(m.method), to_string(a.status), a.from_s, a.to_s,
                                         a.from_epoch, a.to_epoch, a.check, a.reason));
  }
}

}  // namespace detail
}  // namespace meridian::nav
