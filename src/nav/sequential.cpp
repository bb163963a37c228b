// The sequential ship-position adjustment (spec §4), its backward correction (§4.2) and the
// satellite-fix closure (§5). The adjustment is the filter module's Kalman filter: carrying
// the solution by DR with Q_ΔX and solving the epoch's reduced LOPs with the prior weight
// (Q_X̂ + Q_ΔX)⁻¹ is exactly its predict and update (docs/navigation.md).
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/filter/information_filter.hpp"
#include "meridian/filter/two_filter_smoother.hpp"
#include "methods.hpp"

namespace meridian::nav::detail {

namespace {

// The velocity bias W of methods I and II (spec §4.1), the correction added to the DR velocity,
// updated after each epoch's observations from the adjusted position X̂_i against the pure DR
// X_i⁰: method I the running mean of W_i = (X̂_i − X_i⁰)/t_i; method II per segment J of
// segment_s, Ŵ_J = ((J−1)·Ŵ_{J−1} + 2·W̄_J)/(J+1) (Ŵ_1 = method I over the first segment).
class BiasTracker {
 public:
  BiasTracker(const Prepared& p, BiasMethod method)
      : p_(p), method_(method), seg_start_t_(p.t[0]), seg_start_x_(p.initial_x) {}

  /// The bias to add to the DR velocity over the next interval.
  const Eigen::Vector2d& in_use() const { return w_use_; }

  /// After epoch k: x_hat its adjusted position, informed whether it used an observation.
  void after_epoch(std::size_t k, const Eigen::Vector2d& x_hat, bool informed) {
    const double tk = p_.t[k] - p_.t[0];
    if (k == 0) dr0_ = x_hat - p_.dr[0];  // X⁰: pure DR from the adjusted X̂_0
    // Method I (and method II in its first segment, which has no segment before it).
    if (method_ != BiasMethod::None && informed && tk > 0.0 && tk >= p_.input->options.bias_start_s) {
      const Eigen::Vector2d wi = (x_hat - (p_.dr[k] + dr0_)) / tk;  // (X̂_i − X_i⁰)/t_i
      ++w_count_;
      w_mean_ = ((static_cast<double>(w_count_) - 1.0) * w_mean_ + wi) / static_cast<double>(w_count_);
      if (method_ == BiasMethod::I) w_use_ = w_mean_;
    }
    if (method_ == BiasMethod::II) segments(k, x_hat, informed);
  }

 private:
  void segments(std::size_t k, const Eigen::Vector2d& x_hat, bool informed) {
    const double seg = p_.input->options.segment_s;
    if (k == 0) seg_start_x_ = x_hat;
    if (k > 0) seg_dr_ += p_.incr[k];
    const double ts = p_.t[k] - seg_start_t_;
    if (informed && ts > 0.0 && ts >= std::min(p_.input->options.bias_start_s, 0.5 * seg)) {
      const Eigen::Vector2d wi = (x_hat - (seg_start_x_ + seg_dr_)) / ts;
      ++seg_count_;
      seg_mean_ = ((static_cast<double>(seg_count_) - 1.0) * seg_mean_ + wi) / static_cast<double>(seg_count_);
    }
    if (segment_ == 1) w_use_ = w_mean_;  // segment 1: method I
    if (ts < seg - 1e-9) return;
    // Segment J ends here: Ŵ_J = ((J−1)·Ŵ_{J−1} + 2·W̄_J)/(J+1).
    const double J = static_cast<double>(segment_);
    if (segment_ == 1)
      w_hat_ = w_mean_;  // Ŵ_1 = W̄_1, method I over the first segment
    else if (seg_count_ > 0)
      w_hat_ = ((J - 1.0) * w_hat_ + 2.0 * seg_mean_) / (J + 1.0);
    w_use_ = w_hat_;
    ++segment_;
    seg_start_t_ = p_.t[k];
    seg_start_x_ = x_hat;
    seg_dr_.setZero();
    seg_mean_.setZero();
    seg_count_ = 0;
  }

  const Prepared& p_;
  BiasMethod method_;
  Eigen::Vector2d w_use_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d dr0_ = Eigen::Vector2d::Zero();  // X̂_0 − initial position
  // Method I: running mean over the steps with observations.
  Eigen::Vector2d w_mean_ = Eigen::Vector2d::Zero();
  std::size_t w_count_ = 0;
  // Method II: segments.
  std::size_t segment_ = 1;  // J
  double seg_start_t_;
  Eigen::Vector2d seg_start_x_;                       // adjusted position at the segment start
  Eigen::Vector2d seg_dr_ = Eigen::Vector2d::Zero();  // uncorrected DR since the segment start
  Eigen::Vector2d seg_mean_ = Eigen::Vector2d::Zero();
  std::size_t seg_count_ = 0;
  Eigen::Vector2d w_hat_ = Eigen::Vector2d::Zero();  // Ŵ_{J−1}
};

// The prior of the sequential state: the initial position with the sequential methods' σ, the
// chain parameters at 0 with their prior σ.
template <int N>
filter::Estimate<N> sequential_prior(const Prepared& p, int size) {
  filter::Estimate<N> init;
  init.x = filter::Vector<N>::Zero(size);
  init.x.template head<2>() = p.initial_x;
  init.P = filter::Matrix<N, N>::Zero(size, size);
  init.P.template topLeftCorner<2, 2>() = p.initial_cov_seq;
  if constexpr (N == Eigen::Dynamic)
    for (int i = 0; i < p.n_params; ++i)
      init.P(2 + i, 2 + i) =
          p.param_prior_sigma[static_cast<std::size_t>(i)] * p.param_prior_sigma[static_cast<std::size_t>(i)];
  return init;
}

}  // namespace

template <int N>
ForwardRun<N> run_sequential(const Prepared& p, Method method, BiasMethod bias_method,
                             const Screening& sc, std::vector<RejectedObservation>& rejected) {
  using Est = filter::Estimate<N>;
  const std::size_t n = p.epochs;
  Layout layout;
  layout.size = 2 + p.n_params;
  layout.params = 2;
  filter::KalmanFilter<N> kf(sequential_prior<N>(p, layout.size));

  ForwardRun<N> run;
  run.filtered.reserve(n);
  run.bias_use.assign(n, Eigen::Vector2d::Zero());
  run.lop_used.assign(p.lops.size(), 0);
  run.fix_used.assign(p.fixes.size(), 0);
  run.before_fix.assign(n, Eigen::Vector2d::Constant(std::nan("")));
  run.result.method = method;
  run.result.track.reserve(n);

  const filter::Matrix<N, N> identity = filter::Matrix<N, N>::Identity(layout.size, layout.size);
  filter::Matrix<N, N> q = filter::Matrix<N, N>::Zero(layout.size, layout.size);
  BiasTracker bias(p, bias_method);
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0) {
      filter::Vector<N> x = kf.estimate().x;
      x.template head<2>() += p.incr[k] + p.dt[k] * bias.in_use();
      q.template topLeftCorner<2, 2>() = p.q_incr_seq[k];
      kf.predict_extended(x, identity, q);
      run.bias_use[k] = bias.in_use();
    }
    const unsigned flags = update_epoch<N>(p, k, kf, layout, bias.in_use(), method, sc, rejected, &run, &run.monitor);
    const Est& est = kf.estimate();
    bias.after_epoch(k, est.x.template head<2>(), (flags & (kUsedLop | kUsedFix)) != 0);
    TrackPoint tp = track_point<N>(p.t[k], est, layout);
    tp.bias_north_m_s = bias.in_use()(0);
    tp.bias_east_m_s = bias.in_use()(1);
    tp.flags = flags;
    run.result.track.push_back(tp);
    run.filtered.push_back(est);
  }
  run.result.parameters = chain_parameters<N>(p, kf.estimate(), 2);
  return run;
}

namespace {

// The forward estimate of epoch k combined with a backward information filter over the
// epochs k+1 … jend (§4.2). Backward in deviations e_j = x_j − r_j from a reference that follows
// the corrected DR exactly (r_{j−1} = r_j − Δ_j − W·dt_j, r at P₂ = the forward solution there),
// so e_j = e_{j−1} + w: no input term in the information filter; the LOPs are linearised at r_j.
// Steps without observations are merged (Φ = I: the Q's add).
template <int N>
filter::Estimate<N> combine_with_backward(const Prepared& p, const ForwardRun<N>& fw, std::size_t k,
                                          std::size_t jend, const Layout& layout) {
  const Input& in = *p.input;
  const int size = layout.size;
  const filter::Matrix<N, N> identity = filter::Matrix<N, N>::Identity(size, size);
  filter::BackwardInformationFilter<N> bif(static_cast<Eigen::Index>(jend), size);
  filter::Vector<N> ref = fw.filtered[jend].x;  // chain parameters stay at their P₂ values
  filter::Matrix<N, N> q_acc = filter::Matrix<N, N>::Zero(size, size);
  bool pending = false;
  const auto flush = [&] {
    if (pending) {
      bif.predict(identity, q_acc);  // merged steps down to epoch j
      q_acc.setZero();
      pending = false;
    }
  };
  for (std::size_t j = jend; j > k; --j) {
    // observations of epoch j that the forward run used, one at a time (independent)
    for (std::size_t i = p.lop_begin[j]; i < p.lop_begin[j + 1]; ++i) {
      if (!fw.lop_used[i]) continue;
      const Reduced& red = p.lops[i];
      const Lop& lop = in.lops[red.index];
      const Eigen::Vector2d pos = ref.template head<2>() + red.delta + red.dt_s * fw.bias_use[j];
      const LopEvaluation ev = evaluate_lop(p, lop, pos, ref, layout);
      if (!ev.ok) continue;
      flush();
      const double var = lop.sigma_m * lop.sigma_m + ev.h_position.dot(red.q_delta_seq * ev.h_position.transpose());
      bif.update(filter::Vector<1>::Constant(lop.value_m - ev.computed_m), lop_row<N>(ev, layout, red.dt_s),
                 filter::Matrix<1, 1>::Constant(var));
    }
    for (std::size_t i = p.fix_begin[j]; i < p.fix_begin[j + 1]; ++i) {
      if (!fw.fix_used[i]) continue;
      flush();
      const Reduced& red = p.fixes[i];
      const Fix& f = in.fixes[red.index];
      const Eigen::Vector2d pos = ref.template head<2>() + red.delta + red.dt_s * fw.bias_use[j];
      filter::Matrix<2, N> H = filter::Matrix<2, N>::Zero(2, size);
      H(0, 0) = 1.0;
      H(1, 1) = 1.0;
      const Eigen::Vector2d z = Eigen::Vector2d(f.x_north_m, f.y_east_m) - pos;
      const Eigen::Matrix2d R = f.covariance + red.q_delta_seq;
      bif.update(z, H, R);
    }
    // step j → j−1
    q_acc.template topLeftCorner<2, 2>() += p.q_incr_seq[j];
    pending = true;
    ref.template head<2>() -= p.incr[j] + p.dt[j] * fw.bias_use[j];
  }
  if (pending) bif.predict(identity, q_acc);
  // Information about x_k = r_k + e_k: y_x = y_e + Y·r_k.
  const filter::Matrix<N, N>& Y = bif.information();
  const filter::Vector<N> y = bif.information_vector() + Y * ref;
  return filter::combine_information(fw.filtered[k], Y, y, static_cast<Eigen::Index>(k));
}

}  // namespace

template <int N>
MethodResult run_backward(const Prepared& p, const ForwardRun<N>& fw) {
  using Est = filter::Estimate<N>;
  const std::size_t n = p.epochs;
  const int size = static_cast<int>(fw.filtered.front().x.size());
  Layout layout;
  layout.size = size;
  MethodResult out;
  out.method = Method::Backward;
  out.track.reserve(n);
  const double window = p.input->options.backward_window_s;
  std::size_t jend = 0;
  for (std::size_t k = 0; k < n; ++k) {
    while (jend + 1 < n && p.t[jend + 1] <= p.t[k] + window + 1e-9) ++jend;
    if (jend < k) jend = k;
    const Est combined = jend > k ? combine_with_backward<N>(p, fw, k, jend, layout) : fw.filtered[k];
    TrackPoint tp = track_point<N>(p.t[k], combined, layout);
    tp.bias_north_m_s = fw.result.track[k].bias_north_m_s;
    tp.bias_east_m_s = fw.result.track[k].bias_east_m_s;
    tp.flags = fw.result.track[k].flags;
    out.track.push_back(tp);
    if (k + 1 == n) out.parameters = chain_parameters<N>(p, combined, 2);
  }
  return out;
}

template <int N>
MethodResult run_fix_closure(const Prepared& p, const ForwardRun<N>& fw) {
  MethodResult out = fw.result;
  out.method = Method::FixClosure;
  std::size_t prev = 0;
  for (std::size_t k = 0; k < p.epochs; ++k) {
    if (!(fw.result.track[k].flags & kUsedFix) || !std::isfinite(fw.before_fix[k](0))) continue;
    const Eigen::Vector2d closure =
        Eigen::Vector2d(fw.result.track[k].x_north_m, fw.result.track[k].y_east_m) -
        fw.before_fix[k];
    const double span = p.t[k] - p.t[prev];
    for (std::size_t j = prev + 1; j < k && span > 0.0; ++j) {
      const double u = (p.t[j] - p.t[prev]) / span;
      out.track[j].x_north_m += u * closure(0);
      out.track[j].y_east_m += u * closure(1);
    }
    prev = k;
  }
  return out;
}

template ForwardRun<2> run_sequential<2>(const Prepared&, Method, BiasMethod, const Screening&,
                                         std::vector<RejectedObservation>&);
template ForwardRun<Eigen::Dynamic> run_sequential<Eigen::Dynamic>(
    const Prepared&, Method, BiasMethod, const Screening&, std::vector<RejectedObservation>&);
template MethodResult run_backward<2>(const Prepared&, const ForwardRun<2>&);
template MethodResult run_backward<Eigen::Dynamic>(const Prepared&, const ForwardRun<Eigen::Dynamic>&);
template MethodResult run_fix_closure<2>(const Prepared&, const ForwardRun<2>&);
template MethodResult run_fix_closure<Eigen::Dynamic>(const Prepared&,
                                                      const ForwardRun<Eigen::Dynamic>&);

}  // namespace meridian::nav::detail
