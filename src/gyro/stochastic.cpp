#include "meridian/gyro/stochastic.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "meridian/adjust/data_snooping.hpp"
#include "meridian/adjust/likelihood.hpp"
#include "meridian/adjust/nonlinear.hpp"
#include "meridian/adjust/statistics.hpp"
#include "meridian/adjust/two_component_reml.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gyro/markov_covariance.hpp"
#include "meridian/gyro/reversal.hpp"

namespace meridian::gyro {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMinusInf = -std::numeric_limits<double>::infinity();
constexpr double kLrtAlpha = 0.05;
constexpr int kMinReadings = 6;
constexpr int kMinReadingsMarkov2 = 8;  // 3 unknowns + 4 covariance parameters + 1
// The drop of the profile restricted likelihood that bounds the correlations a series cannot rule
// out (correlation_envelope): ½·χ²_{0.68}(1) ≈ 0.5, a 1σ profile-likelihood set of ρ.
constexpr double kEnvelopeLikelihoodDrop = 0.5;
// Keep ML estimates this far inside the stationary region.
constexpr double kEdge = 1e-3;

VectorXd to_vector(const std::vector<double>& r) {
  VectorXd l(static_cast<Index>(r.size()));
  for (std::size_t i = 0; i < r.size(); ++i) l(static_cast<Index>(i)) = r[i];
  return l;
}

// A Markov model at fixed ρ: the maximum of the restricted likelihood over the variance
// components (closed-form profile, adjust::maximise_two_component_reml) — what the searches over
// ρ need. The chosen ρ is then fitted by VCE (markov_fit).
struct MarkovEval {
  std::vector<double> rho;
  Eigen::Vector2d theta;  // σ̂_1², σ̂_2² at the maximum
  bool sigma2_zero = false;  // σ̂_2² = 0: the maximum is on that boundary
  double reml = kMinusInf;
};

std::vector<adjust::VarianceComponent> markov_components(const MarkovFactors& f) {
  return {{"sigma1^2", f.C}, {"sigma2^2", f.B}};
}

MarkovFactors factors_for(const std::vector<double>& rho, int n) {
  return rho.size() == 1 ? markov1_factors(n, rho[0]) : markov2_factors(n, rho[0], rho[1]);
}

std::optional<MarkovEval> eval_markov(const MatrixXd& G, const VectorXd& l,
                                      const std::vector<double>& rho) {
  try {
    const MarkovFactors f = factors_for(rho, static_cast<int>(l.size()));
    const auto c = markov_components(f);
    const auto m = adjust::maximise_two_component_reml(G, l, c[0], c[1]);
    if (!std::isfinite(m.reml) || m.at_zero[0]) return std::nullopt;  // D = σ_2²·B·Bᵀ singular
    return MarkovEval{rho, m.components, m.at_zero[1], m.reml};
  } catch (const Error&) {
    return std::nullopt;
  }
}

double implied_lag_correlation(const MatrixXd& D, Index k) {
  const Index n = D.rows();
  double s = 0.0;
  for (Index i = 0; i + k < n; ++i) s += D(i, i + k) / std::sqrt(D(i, i) * D(i + k, i + k));
  return s / static_cast<double>(n - k);
}

std::vector<double> implied_autocorrelation(const MatrixXd& D) {
  std::vector<double> out;
  for (Index k = 0; k < D.rows(); ++k) out.push_back(implied_lag_correlation(D, k));
  return out;
}

// ΔŶ = (GᵀD⁻¹G)⁻¹·GᵀD⁻¹·s: the GLS estimator applied to the signal s.
Eigen::Vector3d estimator_applied(const MatrixXd& G, const adjust::CovarianceFactor& cov,
                                  const VectorXd& s) {
  MatrixXd gw = G;
  cov.whiten(gw);
  VectorXd sw = s;
  cov.whiten(sw);
  return gw.colPivHouseholderQr().solve(sw);
}

// Fill north/amplitude/damping, likelihood and the implied autocorrelation of a model with
// covariance D.
void finish_fit(ModelFit& f, const std::vector<double>& readings, const MatrixXd& D, GlsRoute route,
                int k) {
  const GlsFit g = reversal_gls(readings, D, route);
  f.north = {g.y(0), std::sqrt(g.covariance(0, 0))};
  f.amplitude = {g.y(1), std::sqrt(g.covariance(1, 1))};
  f.damping = {g.y(2), std::sqrt(g.covariance(2, 2))};
  const MatrixXd G = reversal_design(static_cast<int>(readings.size()));
  const auto lik = adjust::gls_log_likelihood(G, to_vector(readings), adjust::CovarianceFactor(D));
  f.log_likelihood = lik.reml;
  f.covariance_parameters = k;
  const double r = static_cast<double>(readings.size()) - 3.0;
  f.aic = -2.0 * f.log_likelihood + 2.0 * k;
  f.bic = -2.0 * f.log_likelihood + k * std::log(r);
  f.aicc = r - k - 1.0 > 0.0 ? f.aic + 2.0 * k * (k + 1.0) / (r - k - 1.0)
                             : std::numeric_limits<double>::infinity();
  f.implied_autocorrelation = implied_autocorrelation(D);
  // The non-linear model (R1) under the same D; a failure leaves it out with the reason.
  try {
    f.r1 = reversal_gls_nonlinear(readings, D);
  } catch (const Error& e) {
    f.r1.reset();
    f.notes.push_back(fmt::format("(R1) GLS not computed: {}", e.message()));
  }
}

// The inverse of a Fisher information (the covariance of the estimates it is the information
// of); none when it is singular or not positive definite.
std::optional<MatrixXd> inverse_information(const MatrixXd& info) {
  const Eigen::LDLT<MatrixXd> ldlt(info);
  const MatrixXd inv = ldlt.solve(MatrixXd::Identity(info.rows(), info.cols()));
  if (ldlt.info() == Eigen::Success && inv.allFinite() && (inv.diagonal().array() > 0.0).all() &&
      ldlt.isPositive())
    return inv;
  return std::nullopt;
}

Uncertain sigma_from_variance(double var, double sd_var) {
  const double s = std::sqrt(std::max(var, 0.0));
  return {s, s > 0.0 && std::isfinite(sd_var) ? sd_var / (2.0 * s) : kNaN};
}

// A Markov model at its chosen ρ with the components fitted by VCE.
struct MarkovVce {
  std::vector<double> rho;
  MarkovFactors factors;
  adjust::VceResult vce;
};

// The search kept only the maximum of the likelihood: VCE at that ρ, started at the maximum (so
// it confirms it in an iteration or two), gives the components with their covariance.
MarkovVce markov_vce(const MarkovEval& scan, const MatrixXd& G, const VectorXd& l,
                     adjust::VceMethod method) {
  MarkovVce x{scan.rho, factors_for(scan.rho, static_cast<int>(l.size())), {}};
  adjust::VceOptions o;
  o.method = method;
  o.initial = scan.theta.cwiseMax(1e-6 * scan.theta.maxCoeff());
  // Started at the maximum it confirms in a few iterations (a boundary component takes ~5 to
  // be clipped); more than 100 means the likelihood is too flat for scoring (see below).
  o.max_iterations = 100;
  try {
    x.vce = adjust::estimate_variance_components(G, l, markov_components(x.factors), o);
  } catch (const NumericalError& err) {
    // Near the edge of the stationary region the likelihood can be so flat along σ_2² that
    // scoring does not settle: keep the maximum of the closed-form profile, with the inverse
    // Fisher information as the covariance of the components.
    x.vce = adjust::VceResult{};
    x.vce.method = method;
    x.vce.components = scan.theta;
    x.vce.clipped = {false, scan.sigma2_zero};
    x.vce.iterations = 0;
    x.vce.covariance = Eigen::Matrix2d::Constant(kNaN);
    const MatrixXd D = x.factors.covariance(scan.theta(0), scan.theta(1));
    std::vector<MatrixXd> deriv{x.factors.q1()};
    if (!scan.sigma2_zero) deriv.push_back(x.factors.q2());
    if (const auto inv = inverse_information(
            adjust::reml_fisher_information(G, adjust::CovarianceFactor(D), deriv))) {
      x.vce.covariance.setZero();
      x.vce.covariance.topLeftCorner(inv->rows(), inv->cols()) = *inv;
    }
    x.vce.notes.push_back(fmt::format(
        "variance-component estimation did not settle at rho = {:.6g} ({}): the components "
        "are the maximum of the restricted likelihood found in closed form, their sigma from "
        "its Fisher information",
        fmt::join(scan.rho, ", "), err.message()));
  }
  return x;
}

// σ of ρ and of the unclipped components of an ML model from the inverse REML Fisher information
// over (ρ…, σ_1², σ_2²) (∂D/∂ρ by central differences): into f.rho_sigma and sd_theta, or a note.
void ml_sigmas(ModelFit& f, const MarkovVce& e, const MatrixXd& G, const MatrixXd& D,
               VectorXd& sd_theta) {
  const Eigen::VectorXd& th = e.vce.components;
  const adjust::CovarianceFactor cov(D);
  std::vector<MatrixXd> deriv;
  const int n = static_cast<int>(D.rows());
  for (std::size_t a = 0; a < e.rho.size(); ++a) {
    const double h = 1e-5;
    std::vector<double> up = e.rho, dn = e.rho;
    up[a] += h;
    dn[a] -= h;
    try {
      deriv.push_back(
          (factors_for(up, n).covariance(th(0), th(1)) - factors_for(dn, n).covariance(th(0), th(1))) /
          (2.0 * h));
    } catch (const InputError&) {
      deriv.clear();
      break;
    }
  }
  if (deriv.empty()) {
    f.notes.push_back("rho is at the edge of the stationary region: sigma of rho not stated");
    return;
  }
  std::vector<int> comp_index;
  for (int k = 0; k < 2; ++k)
    if (!e.vce.clipped[static_cast<std::size_t>(k)]) {
      deriv.push_back(k == 0 ? e.factors.q1() : e.factors.q2());
      comp_index.push_back(k);
    }
  const auto inv = inverse_information(adjust::reml_fisher_information(G, cov, deriv));
  if (!inv) {
    f.notes.push_back("the Fisher information of rho is singular: sigma of rho not stated");
    return;
  }
  for (std::size_t a = 0; a < e.rho.size(); ++a)
    f.rho_sigma[a] = std::sqrt((*inv)(static_cast<Index>(a), static_cast<Index>(a)));
  for (std::size_t j = 0; j < comp_index.size(); ++j) {
    const auto idx = static_cast<Index>(e.rho.size() + j);
    sd_theta(comp_index[j]) = std::sqrt((*inv)(idx, idx));
  }
}

ModelFit markov_fit(StochasticModel model, const MarkovEval& scan,
                    const std::vector<double>& readings, const MatrixXd& G, const VectorXd& l,
                    GlsRoute route, adjust::VceMethod method, bool ml) {
  const MarkovVce e = markov_vce(scan, G, l, method);
  ModelFit f;
  f.model = model;
  f.rho = e.rho;
  const Eigen::VectorXd& th = e.vce.components;
  const MatrixXd D = e.factors.covariance(th(0), th(1));
  finish_fit(f, readings, D, route, static_cast<int>(e.rho.size()) + 2);
  f.vce_iterations = e.vce.iterations;
  f.notes = e.vce.notes;
  // σ of the components from the VCE; for ML models from the Fisher information over (ρ, θ).
  VectorXd sd_theta(2);
  for (int k = 0; k < 2; ++k) sd_theta(k) = e.vce.sigma(k);
  f.rho_sigma.assign(e.rho.size(), kNaN);
  if (ml) ml_sigmas(f, e, G, D, sd_theta);
  f.sigma1 = sigma_from_variance(th(0), sd_theta(0));
  f.sigma2 = sigma_from_variance(th(1), sd_theta(1));
  // Signal prediction X̂ = σ_2²·Bᵀ·D⁻¹·(L − G·Ŷ) and its influence.
  const adjust::CovarianceFactor cov(D);
  const VectorXd resid = l - G * Eigen::Vector3d(f.north.value, f.amplitude.value, f.damping.value);
  VectorXd rw = resid;
  cov.whiten(rw);
  MatrixXd bw = e.factors.B;
  cov.whiten(bw);
  const VectorXd xhat = th(1) * (bw.transpose() * rw);
  f.signal_influence = estimator_applied(G, cov, e.factors.B * xhat);
  return f;
}

// Golden-section maximisation of f on [a, b].
std::pair<double, double> golden_max(const std::function<double(double)>& fn, double a, double b,
                                     double tol) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = fn(c), fd = fn(d);
  while (b - a > tol) {
    if (fc >= fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - g * (b - a);
      fc = fn(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + g * (b - a);
      fd = fn(d);
    }
  }
  return fc >= fd ? std::pair{c, fc} : std::pair{d, fd};
}

// Nelder–Mead maximisation in 2-D (f = −∞ outside the domain).
std::pair<Eigen::Vector2d, double> nelder_mead_max(
    const std::function<double(const Eigen::Vector2d&)>& fn, Eigen::Vector2d x0, double step,
    double tol, int max_iter) {
  std::array<Eigen::Vector2d, 3> p{x0, x0 + Eigen::Vector2d(step, 0.0),
                                   x0 + Eigen::Vector2d(0.0, step)};
  std::array<double, 3> v{fn(p[0]), fn(p[1]), fn(p[2])};
  for (int it = 0; it < max_iter; ++it) {
    std::array<int, 3> o{0, 1, 2};
    std::sort(o.begin(), o.end(), [&](int i, int j) {
      return v[static_cast<std::size_t>(i)] > v[static_cast<std::size_t>(j)];
    });
    const auto b = static_cast<std::size_t>(o[0]), m = static_cast<std::size_t>(o[1]),
               w = static_cast<std::size_t>(o[2]);
    if ((p[b] - p[w]).norm() < tol && (p[b] - p[m]).norm() < tol) break;
    const Eigen::Vector2d c = 0.5 * (p[b] + p[m]);
    const Eigen::Vector2d r = c + (c - p[w]);
    const double fr = fn(r);
    if (fr > v[b]) {
      const Eigen::Vector2d ex = c + 2.0 * (c - p[w]);
      const double fe = fn(ex);
      if (fe > fr) {
        p[w] = ex;
        v[w] = fe;
      } else {
        p[w] = r;
        v[w] = fr;
      }
    } else if (fr > v[m]) {
      p[w] = r;
      v[w] = fr;
    } else {
      const Eigen::Vector2d ct = c + 0.5 * (p[w] - c);
      const double fct = fn(ct);
      if (fct > v[w]) {
        p[w] = ct;
        v[w] = fct;
      } else {
        for (std::size_t i = 0; i < 3; ++i)
          if (i != b) {
            p[i] = p[b] + 0.5 * (p[i] - p[b]);
            v[i] = fn(p[i]);
          }
      }
    }
  }
  std::size_t best = 0;
  for (std::size_t i = 1; i < 3; ++i)
    if (v[i] > v[best]) best = i;
  return {p[best], v[best]};
}

// The C-type models: fit a·f_b(k) (and ω) to the empirical autocovariance by least squares
// over a grid of the shape parameters (a in closed form for each shape).
struct CovFunction {
  StochasticModel model;
  std::vector<double> params;  // b or (b, ω)
  double a = 0.0;              // LS amplitude of the autocovariance fit (not used for D)
  int ib = 0, iw = 0;          // grid indices of b and ω
};

constexpr int kShapeGridB = 120;  // b from 0.1 to 100 lags, logarithmically
constexpr int kShapeGridW = 60;   // ω = π/60 … π
constexpr std::size_t kMinLagsDampedCosine = 5;

double cov_shape(StochasticModel m, const std::vector<double>& p, double k) {
  switch (m) {
    case StochasticModel::Exponential:
      return std::exp(-k / p[0]);
    case StochasticModel::Gaussian:
      return std::exp(-(k / p[0]) * (k / p[0]));
    default:
      return std::exp(-k / p[0]) * std::cos(p[1] * k);
  }
}

std::optional<CovFunction> fit_cov_function(StochasticModel m, const std::vector<double>& chat) {
  const auto K = chat.size();
  std::optional<CovFunction> best;
  double best_ss = std::numeric_limits<double>::infinity();
  const int nb = kShapeGridB;
  const int nw = m == StochasticModel::DampedCosine ? kShapeGridW : 1;
  for (int ib = 0; ib < nb; ++ib) {
    // b from 0.1 to 100 lags, logarithmically
    const double b = 0.1 * std::pow(1000.0, static_cast<double>(ib) / (nb - 1));
    for (int iw = 0; iw < nw; ++iw) {
      std::vector<double> p{b};
      if (m == StochasticModel::DampedCosine) p.push_back(M_PI * (iw + 1) / nw);
      double sff = 0.0, sfc = 0.0;
      for (std::size_t k = 0; k < K; ++k) {
        const double fk = cov_shape(m, p, static_cast<double>(k));
        sff += fk * fk;
        sfc += fk * chat[k];
      }
      const double a = sfc / sff;
      if (!(a > 0.0)) continue;
      double ss = 0.0;
      for (std::size_t k = 0; k < K; ++k) {
        const double d = chat[k] - a * cov_shape(m, p, static_cast<double>(k));
        ss += d * d;
      }
      if (ss < best_ss) {
        best_ss = ss;
        best = CovFunction{m, p, a, ib, iw};
      }
    }
  }
  return best;
}

// Largest modulus of the roots of the AR characteristic polynomial z² − ρ_1·z − ρ_2 (Markov-1:
// |ρ|); the process is stationary when it is < 1.
double largest_root_modulus(const std::vector<double>& rho) {
  if (rho.size() == 1) return std::fabs(rho[0]);
  const double disc = rho[0] * rho[0] + 4.0 * rho[1];
  if (disc < 0.0) return std::sqrt(-rho[1]);
  const double sq = std::sqrt(disc);
  return std::max(std::fabs(rho[0] + sq), std::fabs(rho[0] - sq)) / 2.0;
}

bool near(double a, double b) { return std::fabs(a - b) < 1e-9; }

// A Markov-2 grid point whose neighbour on the grid lies outside the AR(2) triangle (or off the
// grid): the maximum may lie beyond the grid.
bool markov2_grid_edge(const std::vector<double>& rho) {
  for (const auto& [d1, d2] : {std::pair{0.1, 0.0}, {-0.1, 0.0}, {0.0, 0.1}, {0.0, -0.1}}) {
    const double a = rho[0] + d1, b = rho[1] + d2;
    if (std::fabs(a) > 0.9 + 1e-9 || std::fabs(b) > 0.9 + 1e-9 || !ar2_stationary(a, b)) return true;
  }
  return false;
}

// The reasons of degeneracy at a bound of the search (grid edges, shape grid ends, a range
// beyond the series), of σ_2 → ∞ and of m_M far beyond white noise's.
std::vector<std::string> edge_reasons(const ModelFit& f, const ModelFit& white, int n) {
  std::vector<std::string> why;
  if (f.model == StochasticModel::Markov1Grid && (near(f.rho[0], 0.1) || near(f.rho[0], 0.9)))
    why.push_back(fmt::format("rho = {:.1f} at the edge of its grid 0.1 ... 0.9: the maximum lies "
                              "beyond the grid",
                              f.rho[0]));
  if (f.model == StochasticModel::Markov2Grid && markov2_grid_edge(f.rho))
    why.push_back(fmt::format("(rho1, rho2) = ({:.1f}, {:.1f}) at the edge of the grid or the "
                              "stationarity triangle: the maximum may lie beyond it",
                              f.rho[0], f.rho[1]));
  if (!f.shape.empty()) {
    const double b = f.shape[0];
    if (b <= 0.1 * (1.0 + 1e-9) || b >= 100.0 * (1.0 - 1e-9))
      why.push_back(fmt::format("shape b = {:.3g} lags at an end of its grid 0.1 ... 100 lags", b));
    else if (b >= n - 1.0)
      why.push_back(fmt::format("correlation range b = {:.3g} lags longer than the series ({} "
                                "readings): a drift, not a noise, and without a nugget term the "
                                "fit is absurd",
                                b, n));
    if (f.shape.size() > 1 && near(f.shape[1], M_PI / kShapeGridW))
      why.push_back(fmt::format("shape omega = {:.3g} rad per lag at the lower end of its grid",
                                f.shape[1]));
  }
  const double sw = white.sigma1.value;
  if (!f.rho.empty() && f.sigma2.value > 100.0 * sw)
    why.push_back(fmt::format("sigma2 {:.3g} -> infinity (more than 100 times the white-noise "
                              "sigma1 {:.3g})",
                              f.sigma2.value, sw));
  if (f.north.sigma > kDegenerateSigmaNorthRatio * white.north.sigma)
    why.push_back(fmt::format("m of the centre {:.3g} is more than {} times white noise's {:.3g}",
                              f.north.sigma, kDegenerateSigmaNorthRatio, white.north.sigma));
  return why;
}

// Why a fit is degenerate (empty: it is not). White noise is the yardstick.
std::string degeneracy_reason(const ModelFit& f, const ModelFit& white, double booked, int n) {
  if (f.model == StochasticModel::WhiteNoise) return {};
  std::vector<std::string> why;
  const double sw = white.sigma1.value;
  if (!f.rho.empty()) {
    if (!(f.sigma1.value >= kDegenerateSigma1Ratio * sw))
      why.push_back(fmt::format(
          "sigma1 -> 0 ({:.3g} against {:.3g} for white noise): the signal term fits the "
          "readings almost exactly and the restricted likelihood has no upper bound there",
          f.sigma1.value, sw));
    else if (std::isfinite(booked) && booked > 0.0 && f.sigma1.value < kDegenerateBookedRatio * booked)
      why.push_back(fmt::format(
          "sigma1 {:.3g} is below {} of the booked sigma of one reading {:.3g}: the signal term "
          "fits the readings better than they can be read",
          f.sigma1.value, kDegenerateBookedRatio, booked));
    const double root = largest_root_modulus(f.rho);
    if (root >= kStationarityEdge)
      why.push_back(f.rho.size() == 1
                        ? fmt::format("rho = {:.3f} at the edge of the stationary region "
                                      "(|rho| >= {})",
                                      f.rho[0], kStationarityEdge)
                        : fmt::format("(rho1, rho2) = ({:.3f}, {:.3f}) at the edge of the "
                                      "stationary region (a root of modulus {:.3f} >= {})",
                                      f.rho[0], f.rho[1], root, kStationarityEdge));
  }
  for (auto& w : edge_reasons(f, white, n)) why.push_back(std::move(w));
  const double dm = std::fabs(f.north.value - white.north.value);
  const double da = std::fabs(f.amplitude.value - white.amplitude.value);
  if (da > kDegenerateShift * sw)
    why.push_back(fmt::format("amplitude {:.2f} against {:.2f} for white noise (more than {} "
                              "times its sigma1 {:.3g} apart)",
                              f.amplitude.value, white.amplitude.value, kDegenerateShift, sw));
  if (dm > kDegenerateShift * sw)
    why.push_back(fmt::format("centre {:.2f} against {:.2f} for white noise (more than {} times "
                              "its sigma1 {:.3g} apart)",
                              f.north.value, white.north.value, kDegenerateShift, sw));
  std::string out;
  for (const auto& w : why) out += (out.empty() ? "" : "; ") + w;
  return out;
}

// The checks of the series itself: σ_1 against the booked σ, and (R2) against the length.
void series_checks(StochasticResult& res, const ModelFit& white, const MatrixXd& G) {
  const int n = res.readings;
  const int dof = n - 3;
  const std::string u = " " + fitted_unit(res.kind);
  const double booked = res.booked_sigma;
  const double s1 = white.sigma1.value;
  bool gross = false;  // a booking error: the decay fitted to such readings means nothing
  if (std::isfinite(booked) && booked > 0.0) {
    const double ratio = s1 / booked;
    const auto t = adjust::global_test(dof * ratio * ratio, dof, kReadingSigmaTestAlpha);
    gross = t.rejected && ratio > kBookingErrorRatio;
    if (t.rejected)
      res.warnings.push_back(fmt::format(
          "sigma1 {:.3g}{} of white noise is {:.1f} times the booked sigma of one reading "
          "{:.3g}{} (global test T = {:.1f} > {:.1f}, {} dof, alpha = {}): {}",
          s1, u, ratio, booked, u, t.vtpv, t.critical_value, dof, kReadingSigmaTestAlpha,
          ratio > kBookingErrorRatio
              ? "booking error? Check the readings (order, sign, degrees and minutes) before "
                "using any model"
              : "the readings scatter more than booked: the booked sigma is optimistic, or the "
                "errors are correlated (compare sigma1 of the Markov models)"));
  }
  // (R2) is (R1) with e^{−iκ} ≈ 1 − iκ; the rest, at the fitted decay, less what G absorbs.
  // κ from (R1) itself, r_i = M + (−1)^i·A·e^{−iκ}, by least squares (M, A linear, κ by golden
  // section from (R2)'s start κ = 2c/A′): (R2)'s own κ is biased by the misfit it has to report.
  const VectorXd l = Eigen::Map<const VectorXd>(res.fitted_readings.data(), n);
  const auto r1_fit = [&](double k, Eigen::Vector2d* ma) {
    MatrixXd H(n, 2);
    for (int i = 1; i <= n; ++i) {
      H(i - 1, 0) = 1.0;
      H(i - 1, 1) = (i % 2 == 0 ? 1.0 : -1.0) * std::exp(-i * k);
    }
    const Eigen::Vector2d x = H.colPivHouseholderQr().solve(l);
    if (ma) *ma = x;
    return -(H * x - l).squaredNorm();
  };
  const double k2 = white.amplitude.value != 0.0 ? 2.0 * white.damping.value / white.amplitude.value : 0.0;
  double kappa = 0.0, a = 0.0;
  if (k2 > 0.0 && std::isfinite(k2) && !gross) {
    kappa = golden_max([&](double k) { return r1_fit(k, nullptr); }, 0.0, 3.0 * k2, 1e-4 * k2).first;
    Eigen::Vector2d ma;
    r1_fit(kappa, &ma);
    a = ma(1);
  }
  if (kappa > 0.0 && std::isfinite(kappa)) {
    VectorXd q(n);
    for (int i = 1; i <= n; ++i) {
      const double x = i * kappa;
      // e^{−x} − 1 + x without cancellation for small x.
      const double rest = x < 1e-3 ? x * x / 2.0 - x * x * x / 6.0 : std::expm1(-x) + x;
      q(i - 1) = (i % 2 == 0 ? 1.0 : -1.0) * a * rest;
    }
    const VectorXd fitted = G * G.colPivHouseholderQr().solve(q);
    res.r2_misfit_rms = std::sqrt((q - fitted).squaredNorm() / n);
    if (res.r2_misfit_rms > kR2MisfitRatio * s1)
      res.warnings.push_back(fmt::format(
          "the series is long for the linearised model (R2): at the fitted decay kappa = "
          "{:.4g} per half period and amplitude {:.4g}{} the neglected term A·κ²i²/2 reaches "
          "{:.3g}{} at i = {} and leaves an rms misfit of {:.3g}{} ({:.0f} % of the white-noise "
          "sigma1 {:.3g}{}): the correlated-error models partly model this misfit; analyse "
          "shorter series (the first ~{} readings)",
          kappa, std::fabs(a), u, std::fabs(q(n - 1)), u, n, res.r2_misfit_rms, u,
          100.0 * res.r2_misfit_rms / s1, s1, u,
          std::max(6, static_cast<int>(n * std::sqrt(kR2MisfitRatio * s1 / res.r2_misfit_rms)))));
  }
}

// The series in its fitted unit (see the file comment): circle readings unwrapped and taken in
// arc-seconds from the first reading rounded down to a whole degree, scale readings as they are.
StochasticResult series_in_fitted_unit(const StochasticInput& in) {
  const auto& r = in.readings;
  const int n = static_cast<int>(r.size());
  if (n < kMinReadings)
    throw InputError(
        fmt::format("stochastic models: need at least {} readings (3 unknowns M, "
                    "A', c and 2 variance components, + 1), got {}",
                    kMinReadings, n));
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(r[static_cast<std::size_t>(i)]))
      throw InputError(fmt::format("stochastic models: reading {} is not finite", i + 1),
                       ErrorContext{"", std::nullopt, fmt::format("readings[{}]", i)});
  StochasticResult res;
  res.kind = in.kind;
  res.readings = n;
  if (in.kind == SeriesKind::Circle) {
    const std::vector<double> un = unwrap_circle_readings(r);
    res.reference_rad = std::floor(un.front() / units::kDegree) * units::kDegree;
    for (double x : un) res.fitted_readings.push_back(units::rad_to_arcsec(x - res.reference_rad));
    res.booked_sigma = units::rad_to_arcsec(in.booked_sigma);
  } else {
    res.fitted_readings = r;
    res.booked_sigma = in.booked_sigma;
  }
  return res;
}

// What every model of one series is fitted to.
struct Fitting {
  const std::vector<double>& r;  // r_1 … r_n in the fitted unit
  MatrixXd G;                    // the design of (R2)
  VectorXd l;                    // r as a vector
  const StochasticOptions& options;
};

bool has_model(const StochasticResult& res, StochasticModel m) {
  return std::any_of(res.models.begin(), res.models.end(),
                     [&](const ModelFit& f) { return f.model == m; });
}

// White noise (OLS) with the one-component VCE σ̂_0² = vᵀv/(n − 3), the OLS residuals and their
// autocorrelation. Returns the empirical autocovariance ĉ_k, k = 0 … n−1.
std::vector<double> add_white_noise(StochasticResult& res, const Fitting& fit) {
  const int n = res.readings;
  const auto ols =
      adjust::solve_linear(fit.G, fit.l, adjust::CovarianceFactor::diagonal(VectorXd::Ones(n)));
  const double s0sq = ols.vtpv / (n - 3);
  // Residuals at rounding level of the readings: an exact fit.
  const double scale = fit.l.cwiseAbs().maxCoeff();
  if (!(std::sqrt(s0sq) > 1e-12 * scale))
    throw InputError(
        "stochastic models: the readings fit the reversal model exactly (no "
        "scatter): there is nothing to model");
  res.ols_residuals = ols.residuals;
  std::vector<double> chat(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    double s = 0.0;
    for (int i = 0; i + k < n; ++i) s += ols.residuals(i) * ols.residuals(i + k);
    chat[static_cast<std::size_t>(k)] = s / n;
  }
  for (int k = 0; k < n; ++k)
    res.residual_autocorrelation.push_back(chat[static_cast<std::size_t>(k)] / chat[0]);
  ModelFit w;
  w.model = StochasticModel::WhiteNoise;
  const MatrixXd D = s0sq * MatrixXd::Identity(n, n);
  finish_fit(w, fit.r, D, fit.options.route, 1);
  w.sigma1 = {std::sqrt(s0sq), std::sqrt(s0sq) / std::sqrt(2.0 * (n - 3))};
  w.sigma2 = {kNaN, kNaN};
  w.vce_iterations = 1;
  res.models.push_back(w);
  return chat;
}

// The notes of a covariance function whose shape is at an end of its search grid.
void note_shape_at_grid_end(ModelFit& f, const CovFunction& cf) {
  if (cf.ib == 0)
    f.notes.push_back(fmt::format(
        "shape b = {:.3g} lags is at the lower end of its search grid (0.1 … 100 lags): "
        "the fitted function is effectively white noise",
        cf.params[0]));
  else if (cf.ib == kShapeGridB - 1)
    f.notes.push_back(fmt::format(
        "shape b = {:.3g} lags is at the upper end of its search grid (0.1 … 100 lags): "
        "a correlation that does not decay over the series (a drift) is not identified",
        cf.params[0]));
  if (f.model == StochasticModel::DampedCosine && cf.iw == 0)
    f.notes.push_back(fmt::format(
        "shape omega = {:.3g} rad per lag is at the lower end of its search grid "
        "(pi/60 … pi)",
        cf.params[1]));
}

// One C-type model: the shape from the autocovariance ĉ_k (lags `head`), the amplitude by REML at
// that shape (dof-corrected). Left out with a note when it has no fit or its D is not positive
// definite.
void add_covariance_function(StochasticResult& res, const Fitting& fit, StochasticModel m,
                             const std::vector<double>& head) {
  const int n = res.readings;
  const auto cf = fit_cov_function(m, head);
  if (!cf) {
    res.notes.push_back(fmt::format("{}: no positive fit to the autocovariance", to_string(m)));
    return;
  }
  MatrixXd R(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) R(i, j) = cov_shape(m, cf->params, std::abs(i - j));
  try {
    const GlsFit gr = reversal_gls(fit.r, R, fit.options.route);
    VectorXd vw = gr.residuals;
    adjust::CovarianceFactor(R).whiten(vw);
    const double a = vw.squaredNorm() / (n - 3);
    ModelFit f;
    f.model = m;
    f.shape = cf->params;
    finish_fit(f, fit.r, a * R, fit.options.route, static_cast<int>(cf->params.size()) + 1);
    f.sigma1 = {std::sqrt(a), std::sqrt(a) / std::sqrt(2.0 * (n - 3))};
    f.sigma2 = {kNaN, kNaN};
    note_shape_at_grid_end(f, *cf);
    res.models.push_back(f);
  } catch (const NumericalError& e) {
    res.notes.push_back(
        fmt::format("{}: left out, its covariance matrix is not positive "
                    "definite ({})",
                    to_string(m), e.what()));
  }
}

// The C-type models, fitted to the autocovariance up to lag n/2 (longer lags rest on too few
// products).
void add_covariance_functions(StochasticResult& res, const Fitting& fit,
                              const std::vector<double>& chat) {
  const int n = res.readings;
  const std::vector<double> head(chat.begin(), chat.begin() + std::max(2, n / 2));
  for (StochasticModel m : {StochasticModel::Exponential, StochasticModel::Gaussian,
                            StochasticModel::DampedCosine}) {
    // The damped cosine has 3 parameters (a, b, ω): with fewer than 5 lags it fits the
    // noise of ĉ_k (n = 7, 3 lags: its m was 0.57 of the scatter of M in a Monte Carlo run).
    if (m == StochasticModel::DampedCosine && head.size() < kMinLagsDampedCosine) {
      res.notes.push_back(fmt::format(
          "{}: left out, its 3 parameters need at least {} lags of the autocovariance "
          "(n >= {}), the series gives {}",
          to_string(m), kMinLagsDampedCosine, 2 * kMinLagsDampedCosine, head.size()));
      continue;
    }
    add_covariance_function(res, fit, m, head);
  }
}

// A fitted Markov model; one whose VCE fails at its chosen ρ is left out with a note, and so is
// one the search found no maximum for (`none` says why).
void add_markov(StochasticResult& res, const Fitting& fit, StochasticModel m,
                const std::optional<MarkovEval>& e, bool ml, const char* none) {
  if (!e) {
    res.notes.push_back(fmt::format("{}: {}", to_string(m), none));
    return;
  }
  try {
    res.models.push_back(
        markov_fit(m, *e, fit.r, fit.G, fit.l, fit.options.route, fit.options.vce_method, ml));
  } catch (const NumericalError& err) {
    res.notes.push_back(fmt::format("{}: left out ({})", to_string(m), err.message()));
  }
}

// Markov-1 on the grid ρ = 0.1 … 0.9 and by maximum restricted likelihood: a scan of (−1, 1) in
// steps of 0.05 for the bracket, then golden section.
void add_markov1(StochasticResult& res, const Fitting& fit) {
  const MatrixXd& G = fit.G;
  const VectorXd& l = fit.l;
  std::optional<MarkovEval> m1_grid;
  for (int k = 1; k <= 9; ++k) {
    auto e = eval_markov(G, l, {0.1 * k});
    if (e && (!m1_grid || e->reml > m1_grid->reml)) m1_grid = std::move(e);
  }
  std::optional<MarkovEval> m1_ml;
  double best_rho = 0.0, best = kMinusInf;
  for (int k = -19; k <= 19; ++k) {
    const auto e = eval_markov(G, l, {0.05 * k});
    if (e && e->reml > best) {
      best = e->reml;
      best_rho = 0.05 * k;
    }
  }
  if (std::isfinite(best)) {
    const auto fn = [&](double rho) {
      const auto e = eval_markov(G, l, {rho});
      return e ? e->reml : kMinusInf;
    };
    const auto [rho, v] = golden_max(fn, std::max(-1.0 + kEdge, best_rho - 0.05),
                                     std::min(1.0 - kEdge, best_rho + 0.05), 1e-6);
    m1_ml = eval_markov(G, l, {v >= best ? rho : best_rho});
  }
  add_markov(res, fit, StochasticModel::Markov1Grid, m1_grid, false,
             "the restricted likelihood has no maximum at any rho of the grid");
  add_markov(res, fit, StochasticModel::Markov1Ml, m1_ml, true,
             "the restricted likelihood could not be maximised");
}

// Markov-2 on the grid (ρ_1, ρ_2) ∈ {−0.9, …, 0.9}² inside the AR(2) triangle, which is also the
// likelihood surface of the result; the best grid point.
std::optional<MarkovEval> markov2_grid(StochasticResult& res, const Fitting& fit) {
  for (int k = -9; k <= 9; ++k) {
    res.rho1_grid.push_back(0.1 * k);
    res.rho2_grid.push_back(0.1 * k);
  }
  res.markov2_surface = MatrixXd::Constant(19, 19, kNaN);
  std::optional<MarkovEval> best;
  for (int a = 0; a < 19; ++a) {
    for (int b = 0; b < 19; ++b) {
      const double r1 = res.rho1_grid[static_cast<std::size_t>(a)];
      const double r2 = res.rho2_grid[static_cast<std::size_t>(b)];
      if (!ar2_stationary(r1, r2)) continue;
      auto e = eval_markov(fit.G, fit.l, {r1, r2});
      if (!e) continue;
      res.markov2_surface(a, b) = e->reml;
      if (!best || e->reml > best->reml) best = std::move(e);
    }
  }
  return best;
}

// Markov-2 on the grid and by maximum restricted likelihood (Nelder–Mead from the best grid
// point, strictly inside the triangle).
void add_markov2(StochasticResult& res, const Fitting& fit, Progress* progress) {
  const std::optional<MarkovEval> m2_grid = markov2_grid(res, fit);
  add_markov(res, fit, StochasticModel::Markov2Grid, m2_grid, false,
             "the restricted likelihood has no maximum at any (rho1, rho2) of the grid");
  if (!m2_grid) return;
  report_progress(progress, 3, 5, "Markov-2 ML");
  const auto fn = [&](const Eigen::Vector2d& p) {
    // Strictly inside the triangle, kEdge from its sides.
    if (!(p(0) + p(1) < 1.0 - kEdge && p(1) - p(0) < 1.0 - kEdge && std::fabs(p(1)) < 1.0 - kEdge))
      return kMinusInf;
    const auto e = eval_markov(fit.G, fit.l, {p(0), p(1)});
    return e ? e->reml : kMinusInf;
  };
  const Eigen::Vector2d x0(m2_grid->rho[0], m2_grid->rho[1]);
  // Start inside the triangle (the grid point may sit on its edge region).
  const auto [p, v] = nelder_mead_max(fn, x0, -0.05, 1e-6, 400);
  const Eigen::Vector2d best = v >= m2_grid->reml ? p : x0;
  add_markov(res, fit, StochasticModel::Markov2Ml, eval_markov(fit.G, fit.l, {best(0), best(1)}),
             true, "the restricted likelihood could not be maximised");
}

// Mark the degenerate fits (degeneracy_reason; white noise is the yardstick) with a note each.
void mark_degenerate(StochasticResult& res) {
  const ModelFit& white = res.fit(StochasticModel::WhiteNoise);
  for (auto& f : res.models) {
    f.degenerate_reason = degeneracy_reason(f, white, res.booked_sigma, res.readings);
    f.degenerate = !f.degenerate_reason.empty();
    if (f.degenerate)
      res.notes.push_back(fmt::format(
          "{} is degenerate ({}): it is shown but not recommended, not used in the "
          "likelihood-ratio tests and not used as the signal for the other models' influence",
          to_string(f.model), f.degenerate_reason));
  }
}

bool usable(const StochasticResult& res, StochasticModel m) {
  return has_model(res, m) && !res.fit(m).degenerate;
}

// The signal B·X̂ predicted by the non-degenerate ML Markov model of smaller BIC (else the grid
// model of smaller BIC); none when every Markov model is degenerate.
std::optional<VectorXd> predicted_signal(const StochasticResult& res, const Fitting& fit) {
  const ModelFit* ref = nullptr;
  for (const auto& group : {std::array{StochasticModel::Markov1Ml, StochasticModel::Markov2Ml},
                            std::array{StochasticModel::Markov1Grid, StochasticModel::Markov2Grid}}) {
    for (StochasticModel m : group)
      if (usable(res, m) && (!ref || res.fit(m).bic < ref->bic)) ref = &res.fit(m);
    if (ref) break;
  }
  if (!ref) return std::nullopt;
  const MarkovFactors fac = factors_for(ref->rho, res.readings);
  const double s1 = ref->sigma1.value, s2 = ref->sigma2.value;
  const MatrixXd Dref = fac.covariance(s1 * s1, s2 * s2);
  const adjust::CovarianceFactor cref(Dref);
  VectorXd rw =
      fit.l - fit.G * Eigen::Vector3d(ref->north.value, ref->amplitude.value, ref->damping.value);
  cref.whiten(rw);
  MatrixXd bw = fac.B;
  cref.whiten(bw);
  return VectorXd(fac.B * (s2 * s2 * (bw.transpose() * rw)));
}

// Signal influence of the models without a signal term of their own: their estimator applied to
// the predicted signal (NaN when there is none).
void add_signal_influence(StochasticResult& res, const Fitting& fit) {
  const int n = res.readings;
  const std::optional<VectorXd> signal = predicted_signal(res, fit);
  if (!signal)
    res.notes.push_back(
        "every Markov model is degenerate: the signal influence of white noise and the "
        "covariance-function models is not stated");
  for (auto& f : res.models) {
    const bool own_signal = !f.rho.empty();
    if (own_signal) continue;
    if (!signal) {
      f.signal_influence = Eigen::Vector3d::Constant(kNaN);
    } else if (f.model == StochasticModel::WhiteNoise) {
      f.signal_influence =
          estimator_applied(fit.G, adjust::CovarianceFactor::diagonal(VectorXd::Ones(n)), *signal);
    } else {
      MatrixXd Dc(n, n);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
          Dc(i, j) = f.sigma1.value * f.sigma1.value * cov_shape(f.model, f.shape, std::abs(i - j));
      f.signal_influence = estimator_applied(fit.G, adjust::CovarianceFactor(Dc), *signal);
    }
  }
}

// Why model f cannot be recommended (empty: it can).
std::string not_eligible(const ModelFit& f, int n) {
  if (f.degenerate) return "degenerate";
  if (n < minimum_readings_to_recommend(f.model))
    return fmt::format("needs n >= {}", minimum_readings_to_recommend(f.model));
  if (!std::isfinite(f.aicc)) return "AICc undefined (too few readings for its parameters)";
  return {};
}

// Recommendation: white noise unless an eligible correlated model (not degenerate, long enough
// series for its family, AICc defined) has an AICc lower by kClearlyBetterAicc; among those the
// smallest AICc (fewer parameters on a tie). With located outliers no correlated model is
// recommended: a correlation fitted to a blunder means nothing.
void recommend(StochasticResult& res) {
  const int n = res.readings;
  const ModelFit& white = res.fit(StochasticModel::WhiteNoise);
  std::size_t white_i = 0, best = 0;
  for (std::size_t i = 0; i < res.models.size(); ++i)
    if (res.models[i].model == StochasticModel::WhiteNoise) white_i = best = i;
  std::vector<std::string> left_out;
  bool any = false;
  for (std::size_t i = 0; i < res.models.size(); ++i) {
    const auto& a = res.models[i];
    if (i == white_i) continue;
    const std::string why = not_eligible(a, n);
    if (!why.empty()) {
      left_out.push_back(fmt::format("{} {}", to_string(a.model), why));
      continue;
    }
    const auto& b = res.models[best];
    if (!any || a.aicc < b.aicc - 1e-9 ||
        (std::fabs(a.aicc - b.aicc) <= 1e-9 && a.covariance_parameters < b.covariance_parameters))
      best = i;
    any = true;
  }
  const std::string gap = left_out.empty() ? "" : fmt::format(" (not eligible: {})", fmt::join(left_out, ", "));
  std::size_t chosen = white_i;
  if (!res.outliers.empty()) {
    std::vector<int> idx;
    for (const auto& o : res.outliers) idx.push_back(o.reading);
    res.recommendation_reason = fmt::format(
        "white noise without reading(s) {} (outliers located by data snooping): no correlated "
        "model is recommended on a series with a blunder",
        fmt::join(idx, ", "));
  } else if (!any) {
    res.recommendation_reason =
        fmt::format("white noise: no correlated model can be recommended{}", gap);
  } else if (res.models[best].aicc <= white.aicc - kClearlyBetterAicc) {
    chosen = best;
    res.recommendation_reason = fmt::format(
        "{}: AICc {:.2f} lower than white noise's {:.2f} by {:.2f} (>= {}), smallest among the "
        "eligible models{}",
        to_string(res.models[best].model), res.models[best].aicc, white.aicc,
        white.aicc - res.models[best].aicc, kClearlyBetterAicc, gap);
  } else {
    res.recommendation_reason = fmt::format(
        "white noise: no correlated model clearly better (best eligible {} has AICc {:.2f} "
        "against {:.2f}, less than {} lower){}",
        to_string(res.models[best].model), res.models[best].aicc, white.aicc, kClearlyBetterAicc,
        gap);
  }
  res.models[chosen].recommended = true;
  res.recommended = static_cast<int>(chosen);
}

// The σ of the estimator M̂ = hᵀl under the stationary Markov-1 correlation R_ij = ρ^|i−j| at
// every ρ = 0, 0.1 … 0.9 whose profile restricted likelihood (σ² profiled out by REML,
// σ̂² = v_Rᵀ R⁻¹ v_R/(n − u)) is within χ²_{0.95}(1)/2 of the best — a profile-likelihood 95 %
// set of ρ: correlations the series cannot rule out. The largest σ and its ρ; G may carry
// mean-shift columns of outliers.
std::pair<double, double> correlation_envelope(const MatrixXd& G, const VectorXd& l,
                                               const VectorXd& h) {
  const auto n = l.size();
  struct Point {
    double rho, reml, sigma;
  };
  std::vector<Point> pts;
  double best = kMinusInf;
  for (int k = 0; k <= 9; ++k) {
    const double rho = 0.1 * k;
    MatrixXd R(n, n);
    for (Index i = 0; i < n; ++i)
      for (Index j = 0; j < n; ++j) R(i, j) = std::pow(rho, static_cast<double>(std::abs(i - j)));
    try {
      const adjust::CovarianceFactor fr(R);
      const auto ls = adjust::solve_linear(G, l, fr);
      const double s2 = ls.vtpv / static_cast<double>(ls.dof);
      const auto lik = adjust::gls_log_likelihood(G, l, adjust::CovarianceFactor(MatrixXd(s2 * R)));
      pts.push_back({rho, lik.reml, std::sqrt(s2 * h.dot(R * h))});
      best = std::max(best, lik.reml);
    } catch (const Error&) {
    }
  }
  const double cut = kEnvelopeLikelihoodDrop;
  std::pair<double, double> out{0.0, 0.0};
  for (const auto& p : pts)
    if (p.reml >= best - cut && p.sigma > out.first) out = {p.sigma, p.rho};
  return out;
}

// h with M̂ = hᵀl for the GLS of G with covariance factor cov (h = D⁻¹G(GᵀD⁻¹G)⁻¹e_0).
VectorXd centre_weights(const MatrixXd& G, const adjust::CovarianceFactor& cov) {
  MatrixXd gw = G;
  cov.whiten(gw);
  MatrixXd Ht = gw * (gw.transpose() * gw).ldlt().solve(MatrixXd::Identity(G.cols(), G.cols()));
  cov.whiten_transposed(Ht);
  return Ht.col(0);
}

// The covariance D of a fitted model (white noise: σ_1²·I), rebuilt from its parameters.
MatrixXd model_covariance(const ModelFit& f, int n) {
  const double s1 = f.sigma1.value;
  if (!f.rho.empty()) {
    const double s2 = std::isfinite(f.sigma2.value) ? f.sigma2.value : 0.0;
    return factors_for(f.rho, n).covariance(s1 * s1, s2 * s2);
  }
  MatrixXd D = MatrixXd::Identity(n, n) * s1 * s1;
  if (!f.shape.empty())
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) D(i, j) = s1 * s1 * cov_shape(f.model, f.shape, std::abs(i - j));
  return D;
}

// The value to use (StochasticResult::answer): see the header.
void set_answer(StochasticResult& res, const Fitting& fit) {
  const int n = res.readings;
  const ModelFit& rec = res.models[static_cast<std::size_t>(res.recommended)];
  MatrixXd G = fit.G;
  VectorXd h;
  int dof = n - 3;
  if (res.without_outliers) {
    for (const auto& o : res.outliers) {
      G.conservativeResize(Eigen::NoChange, G.cols() + 1);
      G.col(G.cols() - 1) = VectorXd::Unit(n, o.reading - 1);
    }
    res.answer = res.without_outliers->north;
    dof = res.without_outliers->dof;
    res.answer_basis = "white noise without the outliers, sigma from the remaining readings";
    h = centre_weights(G, adjust::CovarianceFactor::diagonal(VectorXd::Ones(n)));
  } else {
    res.answer = rec.north;
    res.answer_basis = fmt::format("{} (its own sigma)", to_string(rec.model));
    h = centre_weights(G, adjust::CovarianceFactor(model_covariance(rec, n)));
    // The same estimator under the covariance of every other non-degenerate model.
    for (const auto& f : res.models) {
      if (f.degenerate || &f == &rec) continue;
      try {
        const double s = std::sqrt(h.dot(model_covariance(f, n) * h));
        if (s > res.answer.sigma) {
          res.answer.sigma = s;
          res.answer_basis = fmt::format("the estimator of {} under the covariance of {}",
                                         to_string(rec.model), to_string(f.model));
        }
      } catch (const Error&) {
      }
    }
  }
  const auto [s, rho] = correlation_envelope(G, fit.l, h);
  if (s > res.answer.sigma) {
    res.answer.sigma = s;
    res.answer_basis = fmt::format(
        "{}, under a stationary Markov-1 correlation rho = {:.1f} that the series cannot rule out "
        "(profile likelihood within {} of its maximum)",
        res.without_outliers ? "white noise without the outliers" : to_string(rec.model), rho,
        kEnvelopeLikelihoodDrop);
  }
  res.answer_half95 = adjust::student_t_two_sided_critical(0.05, dof) * res.answer.sigma;
}

// Data snooping of the readings under white noise (σ from the other readings), iterated, and the
// white-noise fit without the located outliers. At most one outlier per 5 degrees of freedom.
void snoop(StochasticResult& res, const Fitting& fit) {
  const int n = res.readings;
  adjust::SnoopingOptions o;
  o.alpha0 = kSnoopingAlpha0;
  o.max_outliers = std::max(1, (n - 3) / 5);
  const auto s = adjust::iterated_data_snooping(
      fit.G, fit.l, adjust::CovarianceFactor::diagonal(VectorXd::Ones(n)), o);
  if (s.outliers.empty()) return;
  for (const auto& x : s.outliers)
    res.outliers.push_back({x.index + 1, x.w, x.t, x.critical, x.dof, {x.error, x.sigma_error}});
  const auto& r = s.final_fit;
  OutlierFreeFit w;
  w.north = {r.x(0), r.sigma_aposteriori(0)};
  w.amplitude = {r.x(1), r.sigma_aposteriori(1)};
  w.sigma1 = r.sigma0;
  w.readings_used = n - static_cast<int>(s.outliers.size());
  w.dof = r.dof;
  res.without_outliers = w;
}

// The likelihood-ratio test of null_m against alt, when both are fitted and non-degenerate.
void add_likelihood_ratio_test(StochasticResult& res, StochasticModel null_m, StochasticModel alt,
                               int dof) {
  if (!has_model(res, null_m) || !has_model(res, alt)) return;
  if (!usable(res, null_m) || !usable(res, alt)) {
    res.notes.push_back(fmt::format("likelihood-ratio test {} against {} not made: {} is degenerate",
                                    to_string(null_m), to_string(alt),
                                    to_string(usable(res, null_m) ? alt : null_m)));
    return;
  }
  LikelihoodRatioTest t;
  t.null_model = null_m;
  t.alternative = alt;
  t.statistic = std::max(0.0, 2.0 * (res.fit(alt).log_likelihood - res.fit(null_m).log_likelihood));
  t.dof = dof;
  t.p_value = adjust::chi_squared_upper_probability(t.statistic, dof);
  t.rejected = t.p_value < kLrtAlpha;
  res.tests.push_back(t);
}

void add_likelihood_ratio_tests(StochasticResult& res) {
  add_likelihood_ratio_test(res, StochasticModel::WhiteNoise, StochasticModel::Markov1Ml, 2);
  add_likelihood_ratio_test(res, StochasticModel::Markov1Ml, StochasticModel::Markov2Ml, 1);
}

}  // namespace

int minimum_readings_to_recommend(StochasticModel m) {
  switch (m) {
    case StochasticModel::WhiteNoise:
      return kMinReadings;
    case StochasticModel::Exponential:
    case StochasticModel::Markov1Grid:
    case StochasticModel::Markov1Ml:
      return 10;
    case StochasticModel::Gaussian:
      return 12;
    case StochasticModel::DampedCosine:
    case StochasticModel::Markov2Grid:
    case StochasticModel::Markov2Ml:
      return 15;
  }
  return kMinReadings;
}

double interval95_factor(int readings) {
  if (readings < 4)
    throw InputError(fmt::format("95 % interval: needs n >= 4 readings, got {}", readings));
  return adjust::student_t_two_sided_critical(0.05, readings - 3);
}

std::string fitted_unit(SeriesKind kind) { return kind == SeriesKind::Circle ? "arcsec" : "div"; }

std::string to_string(StochasticModel m) {
  switch (m) {
    case StochasticModel::WhiteNoise:
      return "white-noise";
    case StochasticModel::Exponential:
      return "c-exponential";
    case StochasticModel::Gaussian:
      return "c-gaussian";
    case StochasticModel::DampedCosine:
      return "c-damped-cosine";
    case StochasticModel::Markov1Grid:
      return "markov1-grid";
    case StochasticModel::Markov2Grid:
      return "markov2-grid";
    case StochasticModel::Markov1Ml:
      return "markov1-ml";
    case StochasticModel::Markov2Ml:
      return "markov2-ml";
  }
  return "?";
}

const ModelFit& StochasticResult::fit(StochasticModel m) const {
  for (const auto& f : models)
    if (f.model == m) return f;
  throw InputError(fmt::format("stochastic model {} was not fitted", to_string(m)));
}

MatrixXd reversal_design(int n) {
  if (n < 1) throw InputError(fmt::format("reversal design: needs n >= 1 readings, got {}", n));
  MatrixXd G(n, 3);
  for (int i = 1; i <= n; ++i) {
    const double s = (i % 2 == 0) ? 1.0 : -1.0;  // (−1)^i
    G(i - 1, 0) = 1.0;
    G(i - 1, 1) = s;
    G(i - 1, 2) = -s * (2.0 * i - 1.0);
  }
  return G;
}

GlsFit reversal_gls(const std::vector<double>& readings, const MatrixXd& D, GlsRoute route) {
  const auto n = static_cast<Index>(readings.size());
  if (n < 4)
    throw InputError(
        fmt::format("reversal GLS: needs at least 4 readings (3 unknowns + 1), "
                    "got {}",
                    n));
  if (D.rows() != n || D.cols() != n)
    throw InputError(
        fmt::format("reversal GLS: covariance is {}x{} for {} readings", D.rows(), D.cols(), n));
  const MatrixXd G = reversal_design(static_cast<int>(n));
  const VectorXd l = to_vector(readings);
  GlsFit f;
  if (route == GlsRoute::Whitening) {
    const auto r = adjust::solve_linear(G, l, adjust::CovarianceFactor(D));
    f.y = r.x;
    f.covariance = r.cofactor;
    f.residuals = r.residuals;
    return f;
  }
  // Normal equations: D⁻¹·G and D⁻¹·l by Cholesky solves (no inverse of D).
  const Eigen::LLT<MatrixXd> llt(D);
  if (llt.info() != Eigen::Success)
    throw NumericalError("reversal GLS: the covariance of the readings is not positive definite");
  const MatrixXd pg = llt.solve(G);
  const Eigen::Matrix3d N = G.transpose() * pg;
  const Eigen::LLT<Eigen::Matrix3d> nl(N);
  if (nl.info() != Eigen::Success)
    throw NumericalError("reversal GLS: the normal matrix is not positive definite");
  f.y = nl.solve(pg.transpose() * l);
  f.covariance = nl.solve(Eigen::Matrix3d::Identity());
  f.residuals = G * f.y - l;
  return f;
}

namespace {

// The arguments of reversal_gls_nonlinear, checked as its header says.
void check_r1_arguments(const std::vector<double>& readings, const MatrixXd& D,
                        const R1GlsOptions& options) {
  const auto n = static_cast<Index>(readings.size());
  if (n < 4)
    throw InputError(
        fmt::format("(R1) GLS: needs at least 4 readings (3 unknowns M, A, kappa + 1), got {}", n));
  if (D.rows() != n || D.cols() != n)
    throw InputError(
        fmt::format("(R1) GLS: covariance is {}x{} for {} readings", D.rows(), D.cols(), n),
        ErrorContext{"", std::nullopt, "covariance"});
  for (Index i = 0; i < n; ++i)
    if (!std::isfinite(readings[static_cast<std::size_t>(i)]))
      throw InputError(fmt::format("(R1) GLS: reading {} is not finite", i + 1),
                       ErrorContext{"", std::nullopt, fmt::format("readings[{}]", i)});
  if (!D.allFinite())
    throw InputError("(R1) GLS: the covariance of the readings is not finite",
                     ErrorContext{"", std::nullopt, "covariance"});
  if (options.max_iterations < 1 || !(options.step_tolerance > 0.0))
    throw InputError(fmt::format("(R1) GLS: invalid options (max_iterations {} must be >= 1, "
                                 "step_tolerance {} > 0)",
                                 options.max_iterations, options.step_tolerance));
}

// (R1), r_i = M + (−1)^i·A·e^{−iκ}, i = 1 … n, with its analytic Jacobian.
adjust::NonlinearModel r1_model(Index n) {
  adjust::NonlinearModel model;
  model.predict = [n](const VectorXd& x) {
    VectorXd f(n);
    for (Index k = 0; k < n; ++k) {
      const auto i = static_cast<double>(k + 1);
      const double s = (k + 1) % 2 == 0 ? 1.0 : -1.0;  // (−1)^i
      f(k) = x(0) + s * x(1) * std::exp(-i * x(2));
    }
    return f;
  };
  model.jacobian = [n](const VectorXd& x) {
    MatrixXd J(n, 3);
    for (Index k = 0; k < n; ++k) {
      const auto i = static_cast<double>(k + 1);
      const double s = (k + 1) % 2 == 0 ? 1.0 : -1.0;
      const double e = std::exp(-i * x(2));
      J(k, 0) = 1.0;
      J(k, 1) = s * e;
      J(k, 2) = -s * i * x(1) * e;
    }
    return J;
  };
  return model;
}

}  // namespace

R1GlsFit reversal_gls_nonlinear(const std::vector<double>& readings, const MatrixXd& D,
                                const R1GlsOptions& options) {
  check_r1_arguments(readings, D, options);
  const auto n = static_cast<Index>(readings.size());
  const VectorXd l = to_vector(readings);
  // Start: OLS of (R2) mapped onto (R1) to first order: A = A′ + c, κ = 2c/A.
  const MatrixXd G = reversal_design(static_cast<int>(n));
  const Eigen::Vector3d lin = G.colPivHouseholderQr().solve(l);
  const double a0 = lin(1) + lin(2);
  // An amplitude at rounding level of the readings: no oscillation, κ is not determined.
  if (!(std::fabs(a0) > 1e-12 * l.cwiseAbs().maxCoeff()) || !std::isfinite(a0))
    throw NumericalError(fmt::format(
        "(R1) GLS: the amplitude of the starting (R2) fit is zero ({:.3g}): the readings do not "
        "oscillate and the decay kappa is not determined",
        a0));
  R1GlsFit out;
  out.start = Eigen::Vector3d(lin(0), a0, 2.0 * lin(2) / a0);
  adjust::NonlinearOptions o;
  o.max_iterations = options.max_iterations;
  o.step_tolerance = options.step_tolerance;
  o.step_scale = Eigen::Vector3d(std::fabs(lin(0)) + std::fabs(a0), std::fabs(a0), 1.0);
  adjust::NonlinearResult nl;
  try {
    nl = adjust::solve_nonlinear(r1_model(n), l, D, out.start, o);
  } catch (const Error& e) {
    const std::string msg = "(R1) GLS: " + e.message();
    if (dynamic_cast<const InputError*>(&e)) throw InputError(msg, e.context());
    throw NumericalError(msg, e.context());
  }
  out.y = nl.x;
  out.covariance = nl.cofactor;
  out.residuals = nl.residuals;
  out.vtpv = nl.vtpv;
  out.iterations = nl.iterations;
  out.converged = nl.converged;
  if (!out.y.allFinite() || !out.covariance.allFinite() || !(out.covariance.diagonal().array() >= 0.0).all())
    throw NumericalError(fmt::format(
        "(R1) GLS: the solution or its covariance is not finite (M = {}, A = {}, kappa = {})",
        out.y(0), out.y(1), out.y(2)));
  out.centre = {out.y(0), std::sqrt(out.covariance(0, 0))};
  out.amplitude = {out.y(1), std::sqrt(out.covariance(1, 1))};
  out.decay = {out.y(2), std::sqrt(out.covariance(2, 2))};
  return out;
}

StochasticResult analyse_stochastic(const StochasticInput& input, Progress* progress) {
  StochasticResult res = series_in_fitted_unit(input);
  const int n = res.readings;
  const Fitting fit{res.fitted_readings, reversal_design(n), to_vector(res.fitted_readings), input.options};

  report_progress(progress, 0, 5, "white noise");
  const std::vector<double> chat = add_white_noise(res, fit);
  if (fit.options.covariance_functions) add_covariance_functions(res, fit, chat);
  report_progress(progress, 1, 5, "Markov-1");
  add_markov1(res, fit);
  report_progress(progress, 2, 5, "Markov-2");
  if (!fit.options.markov2) {
    // left out on request
  } else if (n >= kMinReadingsMarkov2) {
    add_markov2(res, fit, progress);
  } else {
    res.notes.push_back(
        fmt::format("Markov-2 models need at least {} readings (3 unknowns, 4 "
                    "covariance parameters, + 1): left out",
                    kMinReadingsMarkov2));
  }
  if (!has_model(res, StochasticModel::Markov1Grid) && !has_model(res, StochasticModel::Markov1Ml))
    throw NumericalError(
        "stochastic models: no Markov model could be fitted (variance-component "
        "estimation failed at every rho)");

  report_progress(progress, 4, 5, "comparison");
  mark_degenerate(res);
  add_signal_influence(res, fit);
  snoop(res, fit);
  recommend(res);
  set_answer(res, fit);
  add_likelihood_ratio_tests(res);
  series_checks(res, res.fit(StochasticModel::WhiteNoise), fit.G);
  report_progress(progress, 5, 5, "done");
  return res;
}

}  // namespace meridian::gyro
