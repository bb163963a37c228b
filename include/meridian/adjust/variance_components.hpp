#pragma once
/// \file variance_components.hpp
/// Variance-component estimation (VCE) for the Gauss–Markov model l + v = A·x with the
/// stochastic model
///
///     D(l) = Σ_k θ_k·Q_k,   k = 1 … K,
///
/// known cofactor matrices Q_k (n×n, symmetric positive semi-definite, their sum with positive
/// weights positive definite) and unknown variance components θ_k ≥ 0 (units of l squared).
///
/// The estimate solves, at the current θ⁰ with D⁰ = Σ θ⁰_k·Q_k, P = (D⁰)⁻¹ and
/// P̄ = P − P·A·(AᵀPA)⁻¹·AᵀP (so P̄·l = −P·v, v = A·x̂ − l):
///
///     Σ_l N_kl·θ_l = r_k,   N_kl = ½·tr(P̄·Q_k·P̄·Q_l),   r_k = ½·vᵀP·Q_k·P·v,
///
/// and is iterated (θ⁰ ← θ) until the a-priori and the a-posteriori components agree. This
/// is least-squares VCE (Teunissen & Amiri-Simkooei 2008, their eq. 36 with the weight that
/// makes it BIQUE for normal data), identical to Fisher scoring of the restricted likelihood
/// (REML; Harville 1977), to iterated MINQUE, and to Helmert's VCE in its general form
/// (Grafarend, Kleusberg & Schaffrin 1980: H·θ = q with H = 2N, q = 2r — Helmert's
/// equations for groups of observations are the special case of block-diagonal Q_k). The
/// converged θ̂ maximise the restricted likelihood (when no component is clipped), and N⁻¹ at
/// θ̂ is the covariance of θ̂ for normally distributed l.
///
/// Two computational routes are offered (VceMethod); they give the same θ̂ to rounding:
/// * LsVce — the traces from the whitened design's orthonormal basis U (L⁻¹·A = U·R,
///   D⁰ = L·Lᵀ): P̄ = L⁻ᵀ(I − U·Uᵀ)L⁻¹, N_kl = ½‖F̄_kᵀ(I − UUᵀ)F̄_l‖²_F with F̄_k = L⁻¹F_k;
/// * Helmert — Helmert's equations written out with the normal matrix N_A = AᵀPA:
///   H_kl = tr(PQ_kPQ_l) − 2·tr(N_A⁻¹·AᵀPQ_kPQ_lPA) + tr(N_A⁻¹·AᵀPQ_kPA·N_A⁻¹·AᵀPQ_lPA),
///   q_k = vᵀPQ_kPv with x̂ from the normal equations (N_A solved by Cholesky).
/// Neither forms an inverse of D: P is applied by whitening with L.
///
/// Negative estimates. A component whose estimate falls below zero (its Q_k explains less than
/// nothing, typical of a short series) is set to zero and held there; the others are
/// re-estimated, and a note says so ("θ_2 (sigma2²) estimated negative (−0.31) at iteration
/// 3: set to 0"). Its σ is then not stated (NaN) and it is excluded from the covariance of θ̂.
///
/// Sources: Teunissen & Amiri-Simkooei (2008) Least-squares variance component estimation,
/// J Geod 82:65–82; Amiri-Simkooei (2007) Least-squares variance component estimation: theory
/// and GPS applications, PhD thesis, TU Delft; Grafarend, Kleusberg & Schaffrin (1980) An
/// introduction to the variance-covariance-component estimation of Helmert type, ZfV
/// 105:161–180; Koch (1999) Parameter estimation and hypothesis testing in linear models,
/// 2nd ed., Springer, §3.6; Harville (1977) JASA 72:320–338.

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "meridian/adjust/least_squares.hpp"
#include "meridian/adjust/likelihood.hpp"

namespace meridian::adjust {

/// One term θ_k·Q_k of the stochastic model, with its cofactor matrix given as a factor:
/// Q_k = F_k·F_kᵀ, F_k n×r_k (r_k ≥ 1). A factor keeps low-rank components (a signal through
/// a few initial states) cheap; a full Q_k can be given through from_cofactor().
struct VarianceComponent {
  std::string name;        ///< for notes and messages, e.g. "sigma1^2"
  Eigen::MatrixXd factor;  ///< F_k (n×r_k), finite

  /// The component with cofactor matrix Q (n×n, symmetric, positive semi-definite), factored
  /// as F = V·Λ^{1/2} from its eigen-decomposition (eigenvalues below 1e-14·λ_max dropped).
  /// Throws InputError when Q is empty, not square, not finite, not symmetric (within 1e-10 of
  /// its largest entry) or has an eigenvalue below −1e-10·λ_max (not semi-definite).
  static VarianceComponent from_cofactor(std::string name, const Eigen::MatrixXd& Q);
};

/// The computational route (both give the same estimates; see the file comment).
enum class VceMethod {
  LsVce,    ///< least-squares VCE / REML scoring through the whitened orthogonal projector
  Helmert,  ///< Helmert's equations through the normal matrix AᵀPA
};

/// "ls-vce", "helmert".
std::string to_string(VceMethod m);

struct VceOptions {
  VceMethod method = VceMethod::LsVce;
  /// θ⁰, the a-priori components (size K, each finite and > 0; units of l squared). Empty:
  /// all 1 (the spec's start, meaningful when l is scaled so that its variance is about 1).
  Eigen::VectorXd initial;
  int max_iterations = 1000;  ///< ≥ 1 (scoring converges linearly; slow near a boundary)
  /// Converged when every |θ_k − θ⁰_k| ≤ tolerance·max_k θ_k (relative to the largest
  /// component, so a component near zero does not stall the iteration); in (0, 1).
  double tolerance = 1e-10;
  /// false: compute only the components, `clipped`, `iterations`, `notes` and `likelihood`
  /// (covariance NaN, adjustment empty) — for profiling the likelihood over other parameters
  /// of the covariance, where only its value is needed.
  bool details = true;
};

struct VceResult {
  Eigen::VectorXd components;  ///< θ̂_k (units of l squared), ≥ 0; exactly 0 when clipped
  /// Covariance of θ̂ (K×K): the inverse of N at θ̂ over the components not clipped; rows and
  /// columns of clipped components are 0.
  Eigen::MatrixXd covariance;
  std::vector<bool> clipped;  ///< the estimate went negative and was set to 0
  int iterations = 0;         ///< updates of θ until convergence (≥ 1)
  VceMethod method = VceMethod::LsVce;
  LeastSquaresResult adjustment;   ///< the GLS with D(θ̂) (a-priori σ0 = 1)
  GlsLikelihood likelihood;        ///< log-likelihoods at θ̂ and x̂
  std::vector<std::string> notes;  ///< clipped components, one sentence each

  /// σ of θ̂_k: sqrt(covariance(k, k)); NaN when component k was clipped. Throws InputError
  /// when k is out of range.
  double sigma(int k) const;
};

/// Estimate the components of D(l) = Σ θ_k·F_k·F_kᵀ for l + v = A·x (A n×u, n > u ≥ 1, full
/// column rank; l size n; every factor n rows; K ≥ 1 components; n − u ≥ K).
/// Throws InputError on mismatched sizes, non-finite input, fewer degrees of freedom than
/// components, or invalid options; NumericalError when D(θ) is not positive definite (also
/// after clipping: "variance components: with sigma2^2 set to 0 the covariance is singular"),
/// when the components cannot be separated (N singular), when every component went negative,
/// or when the iteration does not converge within max_iterations (the message gives the last
/// relative change and the components).
VceResult estimate_variance_components(const Eigen::MatrixXd& A, const Eigen::VectorXd& l,
                                       const std::vector<VarianceComponent>& components,
                                       const VceOptions& options = {});

/// D = Σ θ_k·F_k·F_kᵀ (n×n). Throws InputError when sizes differ.
Eigen::MatrixXd assemble_covariance(const std::vector<VarianceComponent>& components,
                                    const Eigen::VectorXd& theta);

}  // namespace meridian::adjust
