// The modern comparison (spec §6): an extended Kalman filter with position, velocity bias and
// the chain parameters, and its Rauch–Tung–Striebel smoother, both from the filter module.
#include <cmath>
#include <map>

#include "meridian/filter/discretisation.hpp"
#include "meridian/filter/rts_smoother.hpp"
#include "meridian/filter/smoother_storage.hpp"
#include "methods.hpp"

namespace meridian::nav::detail {

namespace {

// Φ and Q_d of position + bias over dt (Van Loan; exact for both bias models): ṗ = W,
// Ẇ = 0 (random walk, density q²) or −W/τ (Gauss–Markov, density 2σ²/τ).
filter::DiscreteModel<4> bias_model(const Options& o, double dt) {
  filter::ContinuousModel<4, 2> m;
  m.F.setZero();
  m.F(0, 2) = 1.0;
  m.F(1, 3) = 1.0;
  double q = o.bias_random_walk_m_s_per_sqrt_s * o.bias_random_walk_m_s_per_sqrt_s;
  if (o.bias_model == BiasModel::GaussMarkov) {
    m.F(2, 2) = m.F(3, 3) = -1.0 / o.bias_correlation_time_s;
    q = 2.0 * o.bias_sigma_m_s * o.bias_sigma_m_s / o.bias_correlation_time_s;
  }
  m.G.setZero();
  m.G(2, 0) = 1.0;
  m.G(3, 1) = 1.0;
  m.q_c = q * Eigen::Matrix2d::Identity();
  return filter::discretise(m, dt);
}

// The EKF's prior: x₀ = x_fix − D − (t_fix − t₀)·W for an initial fix (initial_dt_s = 0
// otherwise): the bias's prior enters the position's and their cross-covariance; the chain
// parameters at 0 with their prior σ.
template <int N>
filter::Estimate<N> ekf_prior(const Prepared& p, int size) {
  const Options& o = p.input->options;
  filter::Estimate<N> init;
  init.x = filter::Vector<N>::Zero(size);
  init.x.template head<2>() = p.initial_x;
  init.P = filter::Matrix<N, N>::Zero(size, size);
  const double wb = o.bias_sigma_m_s * o.bias_sigma_m_s;
  const double dt0 = p.initial_dt_s;
  init.P.template topLeftCorner<2, 2>() = p.initial_cov + dt0 * dt0 * wb * Eigen::Matrix2d::Identity();
  init.P(0, 2) = init.P(2, 0) = init.P(1, 3) = init.P(3, 1) = -dt0 * wb;
  init.P(2, 2) = init.P(3, 3) = wb;
  if constexpr (N == Eigen::Dynamic)
    for (int i = 0; i < p.n_params; ++i)
      init.P(4 + i, 4 + i) =
          p.param_prior_sigma[static_cast<std::size_t>(i)] * p.param_prior_sigma[static_cast<std::size_t>(i)];
  return init;
}

// The RTS smoother over the EKF's records: its track (with the EKF's flags) and, at the first
// epoch, the chain parameters (over the whole line).
template <int N>
MethodResult smooth(const Prepared& p, filter::SmootherStorage<N>& storage, const MethodResult& ekf,
                    const Layout& layout, Progress* progress) {
  const std::size_t n = p.epochs;
  MethodResult rts;
  rts.method = Method::Rts;
  rts.track.resize(n);
  std::size_t done = 0;
  filter::rts_smooth(storage, [&](Eigen::Index k, const filter::Estimate<N>& s) {
    const auto i = static_cast<std::size_t>(k);
    rts.track[i] = track_point<N>(p.t[i], s, layout);
    rts.track[i].flags = ekf.track[i].flags;
    if (i == 0) rts.parameters = chain_parameters<N>(p, s, 4);
    if (progress && (++done % 4096 == 0)) progress->update(n + done, 2 * n, "smoother");
  });
  return rts;
}

}  // namespace

template <int N>
std::vector<MethodResult> run_ekf_rts(const Prepared& p, const Screening& sc,
                                      std::vector<RejectedObservation>& rejected,
                                      Progress* progress, Monitor& ekf_monitor) {
  const Options& o = p.input->options;
  const std::size_t n = p.epochs;
  Layout layout;
  layout.bias = 2;
  layout.params = 4;
  layout.size = 4 + p.n_params;
  const int size = layout.size;
  filter::KalmanFilter<N> kf(ekf_prior<N>(p, size));
  filter::SmootherStorage<N> storage(size, o.storage);

  MethodResult ekf;
  ekf.method = Method::Ekf;
  ekf.track.reserve(n);
  filter::Matrix<N, N> phi = filter::Matrix<N, N>::Identity(size, size);
  filter::Matrix<N, N> q = filter::Matrix<N, N>::Zero(size, size);
  double cached_dt = -1.0;
  filter::DiscreteModel<4> model{filter::Matrix<4, 4>::Identity(), filter::Matrix<4, 4>::Zero()};
  const Eigen::Vector2d no_bias = Eigen::Vector2d::Zero();
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0) {
      if (p.dt[k] != cached_dt) {
        model = bias_model(o, p.dt[k]);
        cached_dt = p.dt[k];
        phi.template topLeftCorner<4, 4>() = model.phi;
      }
      q.template topLeftCorner<4, 4>() = model.q;
      q.template topLeftCorner<2, 2>() += p.q_incr[k];
      filter::Vector<N> x = phi * kf.estimate().x;
      x.template head<2>() += p.incr[k];
      kf.predict_extended(x, phi, q);
    }
    const unsigned flags =
        update_epoch<N>(p, k, kf, layout, no_bias, Method::Ekf, sc, rejected, nullptr, &ekf_monitor);
    // Full records: a navigation line stays in memory, where storing P⁻ is cheaper than
    // recomputing it (the compact layout pays off only when the records spill, docs/filter.md).
    storage.append(kf.predicted(), kf.transition(), kf.estimate());
    TrackPoint tp = track_point<N>(p.t[k], kf.estimate(), layout);
    tp.flags = flags;
    ekf.track.push_back(tp);
    if (progress && (k % 4096 == 0)) progress->update(k, 2 * n, "filter");
  }
  ekf.parameters = chain_parameters<N>(p, kf.estimate(), 4);
  MethodResult rts = smooth<N>(p, storage, ekf, layout, progress);
  std::vector<MethodResult> out;
  out.push_back(std::move(ekf));
  out.push_back(std::move(rts));
  return out;
}

template std::vector<MethodResult> run_ekf_rts<4>(const Prepared&, const Screening&,
                                                  std::vector<RejectedObservation>&, Progress*, Monitor&);
template std::vector<MethodResult> run_ekf_rts<Eigen::Dynamic>(const Prepared&, const Screening&,
                                                               std::vector<RejectedObservation>&,
                                                               Progress*, Monitor&);

}  // namespace meridian::nav::detail
