#pragma once
// The methods of the navigation workflow over a prepared line (private to src/nav). Templates
// on the state size N: fixed (2 for the sequential methods, 4 for the EKF) when the line has
// no chain parameters — no heap traffic in the loops — and Eigen::Dynamic otherwise.
#include <cmath>
#include <cstdint>
#include <vector>

#include <fmt/format.h>

#include "meridian/filter/estimate.hpp"
#include "meridian/filter/kalman_filter.hpp"
#include "prepared.hpp"

namespace meridian::nav::detail {

/// How the observations of an epoch are tested before they are used.
struct Screening {
  Rejection rejection = Rejection::Threshold;
  double threshold_m = 100.0;
  double w_critical = 3.29;      ///< two-sided normal critical value at α
  double fix_chi2_limit = 13.8;  ///< χ²_{1−α}(2)
  double fix_tolerance_m = 200.0;
};

/// The innovations a forward method saw (its self-checks, consistency.cpp).
struct Monitor {
  struct LopTest {
    std::size_t epoch = 0;
    double w = 0.0;  ///< normalised innovation against the predicted state
    bool rejected = false;
  };
  struct FixTest {
    std::size_t index = 0;  ///< into Input::fixes
    std::size_t epoch = 0;
    double chi2 = 0.0;        ///< vᵀS⁻¹v against the state before the fix
    double distance_m = 0.0;  ///< |v|
    bool outlying = false;    ///< flagged by the method's fix test
  };
  std::vector<LopTest> lops;
  std::vector<FixTest> fixes;
};

/// What one forward run used, for the methods built on it (backward, fix closure).
template <int N>
struct ForwardRun {
  std::vector<filter::Estimate<N>> filtered;  ///< per epoch, after its observations
  std::vector<Eigen::Vector2d> bias_use;  ///< bias added to the DR velocity over (t_{k−1}, t_k]
  std::vector<std::uint8_t> lop_used;     ///< per Prepared::lops entry
  std::vector<std::uint8_t> fix_used;     ///< per Prepared::fixes entry
  std::vector<Eigen::Vector2d> before_fix;  ///< per epoch: position before the fix update
  MethodResult result;
  Monitor monitor;
};

enum class BiasMethod { None, I, II };

/// The sequential ship-position adjustment (spec §4, §4.1, §4.3, §4.4); N = 2 + parameters.
template <int N>
ForwardRun<N> run_sequential(const Prepared& p, Method method, BiasMethod bias,
                             const Screening& screening, std::vector<RejectedObservation>& rejected);
/// §4.2: `forward` combined at every epoch with a backward run over backward_window_s.
template <int N>
MethodResult run_backward(const Prepared& p, const ForwardRun<N>& forward);
/// §5: the closures of the fixes of `forward` distributed linearly over their segments.
template <int N>
MethodResult run_fix_closure(const Prepared& p, const ForwardRun<N>& forward);
/// §6: the EKF and its RTS smoother (two results: Ekf, Rts); N = 4 + parameters.
template <int N>
std::vector<MethodResult> run_ekf_rts(const Prepared& p, const Screening& screening,
                                      std::vector<RejectedObservation>& rejected,
                                      Progress* progress, Monitor& ekf_monitor);

/// The self-checks of every method of `res` (spec §6a): `monitors[m]` the innovations of the
/// forward method m (empty for the others). Sets MethodResult::consistency, adds warnings.
void check_consistency(const Prepared& p, const Screening& sc, const std::vector<Monitor>& monitors,
                       Result& res);

/// A track point from an estimate (position block and, with layout.bias ≥ 0, the bias).
template <int N>
TrackPoint track_point(double time_s, const filter::Estimate<N>& e, const Layout& layout) {
  TrackPoint t;
  t.time_s = time_s;
  t.x_north_m = e.x(0);
  t.y_east_m = e.x(1);
  t.covariance = e.P.template topLeftCorner<2, 2>();
  if (layout.bias >= 0) {
    t.bias_north_m_s = e.x(layout.bias);
    t.bias_east_m_s = e.x(layout.bias + 1);
    t.sigma_bias_north_m_s = std::sqrt(e.P(layout.bias, layout.bias));
    t.sigma_bias_east_m_s = std::sqrt(e.P(layout.bias + 1, layout.bias + 1));
  }
  return t;
}

/// The chain parameters of an estimate whose parameters start at state `first` (none for a
/// fixed-size state, which holds none).
template <int N>
std::vector<ChainParameter> chain_parameters(const Prepared& p, const filter::Estimate<N>& e, int first) {
  std::vector<ChainParameter> out;
  if constexpr (N == Eigen::Dynamic)
    for (int i = 0; i < p.n_params; ++i) {
      const auto c = static_cast<std::size_t>(i);
      out.push_back({p.param_chain[c], p.input->chains[p.param_chain[c]].name, p.param_names[c], e.x(first + i),
                     e.sigma(first + i)});
    }
  return out;
}

/// The Jacobian row of a LOP evaluation in a state of `layout` (with the EKF's bias term:
/// the reduction moves the ship by W·dt, so ∂L/∂W = ∂L/∂p·dt).
template <int N>
filter::Matrix<1, N> lop_row(const LopEvaluation& ev, const Layout& layout, double dt_s) {
  filter::Matrix<1, N> h = filter::Matrix<1, N>::Zero(1, layout.size);
  h(0) = ev.h_position(0);
  h(1) = ev.h_position(1);
  if (layout.bias >= 0) {
    h(layout.bias) = ev.h_position(0) * dt_s;
    h(layout.bias + 1) = ev.h_position(1) * dt_s;
  }
  if (ev.scale_state >= 0) h(ev.scale_state) = ev.h_scale;
  if (ev.offset_state >= 0) h(ev.offset_state) = 1.0;
  return h;
}

/// The ship's position at an observation's time: the state's position moved by the reduction
/// (the DR move and the bias: the EKF's from its state, layout.bias, else `bias`).
template <int N>
Eigen::Vector2d reduced_position(const Reduced& r, const filter::Vector<N>& x, const Layout& layout,
                                 const Eigen::Vector2d& bias) {
  const Eigen::Vector2d w = layout.bias >= 0 ? Eigen::Vector2d(x(layout.bias), x(layout.bias + 1)) : bias;
  return Eigen::Vector2d(x.template head<2>() + r.delta + r.dt_s * w);
}

/// The LOPs of epoch k, all tested against the predicted state, the accepted ones solved
/// together (the normal equations of the epoch, spec §4); returns TrackFlag bits.
template <int N>
unsigned update_lops(const Prepared& p, std::size_t k, filter::KalmanFilter<N>& kf, const Layout& layout,
                     const Eigen::Vector2d& bias, Method method, const Screening& sc,
                     std::vector<RejectedObservation>& rejected, ForwardRun<N>* record,
                     Monitor* monitor) {
  const std::size_t b = p.lop_begin[k];
  const std::size_t e = p.lop_begin[k + 1];
  if (e == b) return 0;
  unsigned flags = 0;
  const bool ekf = layout.bias >= 0;
  const filter::Estimate<N>& pred = kf.estimate();
  const auto count = static_cast<Eigen::Index>(e - b);
  filter::Matrix<Eigen::Dynamic, N> H(count, layout.size);
  Eigen::VectorXd nu(count);
  Eigen::VectorXd r(count);
  Eigen::Index m = 0;
  for (std::size_t j = b; j < e; ++j) {
    const Reduced& red = p.lops[j];
    const Lop& lop = p.input->lops[red.index];
    const LopEvaluation ev = evaluate_lop(p, lop, reduced_position<N>(red, pred.x, layout, bias), pred.x, layout);
    RejectedObservation rej;
    rej.kind = RejectedObservation::Kind::Lop;
    rej.index = red.index;
    rej.method = method;
    rej.time_s = lop.time_s;
    if (!ev.ok) {
      rej.misclosure_m = lop.value_m - ev.computed_m;
      rej.reason = fmt::format("the ship is within {:g} m of a station", kMinStationDistance_m);
      rejected.push_back(std::move(rej));
      flags |= kRejectedLop;
      continue;
    }
    const filter::Matrix<1, N> h = lop_row<N>(ev, layout, red.dt_s);
    const Eigen::Matrix2d& qd = ekf ? red.q_delta : red.q_delta_seq;
    const double var = lop.sigma_m * lop.sigma_m + ev.h_position.dot(qd * ev.h_position.transpose());
    const double v = lop.value_m - ev.computed_m;
    const double s = (h * pred.P * h.transpose())(0, 0) + var;
    const double w = v / std::sqrt(s);
    rej.misclosure_m = v;
    const bool reject = sc.rejection == Rejection::Threshold && !ekf && k > 0
                            ? std::abs(v) > sc.threshold_m
                            : std::abs(w) > sc.w_critical;
    if (monitor) monitor->lops.push_back({k, w, reject});
    // The fixed threshold needs a predicted position: the first epoch (spec §4: T_1 is
    // solved by least squares alone) is screened by the w-test, which weighs the prior σ.
    if (sc.rejection == Rejection::Threshold && !ekf && k > 0) {
      if (std::abs(v) > sc.threshold_m) {
        rej.reason = fmt::format("|misclosure| {:.1f} m > {:g} m", std::abs(v), sc.threshold_m);
        rejected.push_back(std::move(rej));
        flags |= kRejectedLop;
        continue;
      }
    } else if (std::abs(w) > sc.w_critical) {
      rej.statistic = std::abs(w);
      rej.reason = fmt::format("|w| = {:.2f} > {:.2f}", std::abs(w), sc.w_critical);
      rejected.push_back(std::move(rej));
      flags |= kRejectedLop;
      continue;
    }
    H.row(m) = h;
    nu(m) = v;
    r(m) = var;
    ++m;
    if (record) record->lop_used[j] = 1;
  }
  if (m > 0) {
    kf.update_extended(nu.head(m), H.topRows(m), r.head(m).asDiagonal().toDenseMatrix());
    flags |= kUsedLop;
  }
  return flags;
}

/// The fixes of epoch k (spec §5): tested against the solution so far, then combined by minimum
/// variance (the update with H = [I 0]); returns TrackFlag bits.
template <int N>
unsigned update_fixes(const Prepared& p, std::size_t k, filter::KalmanFilter<N>& kf, const Layout& layout,
                      const Eigen::Vector2d& bias, Method method, const Screening& sc,
                      std::vector<RejectedObservation>& rejected, ForwardRun<N>* record,
                      Monitor* monitor) {
  unsigned flags = 0;
  const bool ekf = layout.bias >= 0;
  for (std::size_t j = p.fix_begin[k]; j < p.fix_begin[k + 1]; ++j) {
    const Reduced& red = p.fixes[j];
    const Fix& fix = p.input->fixes[red.index];
    const filter::Estimate<N>& cur = kf.estimate();
    if (record) record->before_fix[k] = cur.x.template head<2>();
    const Eigen::Vector2d v = Eigen::Vector2d(fix.x_north_m, fix.y_east_m) - reduced_position<N>(red, cur.x, layout, bias);
    filter::Matrix<2, N> H = filter::Matrix<2, N>::Zero(2, layout.size);
    H(0, 0) = 1.0;
    H(1, 1) = 1.0;
    if (ekf) {
      H(0, layout.bias) = red.dt_s;
      H(1, layout.bias + 1) = red.dt_s;
    }
    const Eigen::Matrix2d R = fix.covariance + (ekf ? red.q_delta : red.q_delta_seq);
    const Eigen::Matrix2d S = H * cur.P * H.transpose() + R;
    const double chi2 = v.dot(S.ldlt().solve(v));
    const bool outlying = v.norm() > sc.fix_tolerance_m || chi2 > sc.fix_chi2_limit;
    if (monitor) monitor->fixes.push_back({red.index, k, chi2, v.norm(), outlying});
    if (outlying) {
      RejectedObservation rej;
      rej.kind = RejectedObservation::Kind::Fix;
      rej.index = red.index;
      rej.method = method;
      rej.time_s = fix.time_s;
      rej.misclosure_m = v.norm();
      rej.statistic = std::sqrt(chi2);
      rej.reason = v.norm() > sc.fix_tolerance_m
                       ? fmt::format("{:.1f} m from the track > fix_tolerance_m {:g}", v.norm(), sc.fix_tolerance_m)
                       : fmt::format("χ²(2) = {:.1f} > {:.1f}", chi2, sc.fix_chi2_limit);
      rejected.push_back(std::move(rej));
      flags |= kFlaggedFix;
      continue;
    }
    kf.update_extended(v, H, R);
    flags |= kUsedFix;
    if (record) record->fix_used[j] = 1;
  }
  return flags;
}

/// The observations of epoch k tested against the filter's current (predicted) state and the
/// accepted ones applied, LOPs first, then fixes; returns TrackFlag bits. `bias` is the velocity
/// bias used to reduce the observations of the sequential methods (the EKF's comes from its
/// state, layout.bias).
template <int N>
unsigned update_epoch(const Prepared& p, std::size_t k, filter::KalmanFilter<N>& kf,
                      const Layout& layout, const Eigen::Vector2d& bias, Method method,
                      const Screening& sc, std::vector<RejectedObservation>& rejected,
                      ForwardRun<N>* record, Monitor* monitor) {
  const unsigned lops = update_lops<N>(p, k, kf, layout, bias, method, sc, rejected, record, monitor);
  return lops | update_fixes<N>(p, k, kf, layout, bias, method, sc, rejected, record, monitor);
}

}  // namespace meridian::nav::detail
