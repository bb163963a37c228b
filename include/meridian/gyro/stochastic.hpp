#pragma once
/// \file stochastic.hpp
/// Stochastic modelling of one reversal-point series (gyro-stochastic spec §4–§5): the same
/// functional model fitted under competing models of the reading errors, compared by their
/// restricted likelihood.
///
/// Functional model: the linearised reversal-point model (R2) of gyro-theodolite.md,
///     r_i = M + (−1)^i·A′ + (−1)^{i+1}·(2i − 1)·c,   i = 1 … n,
/// design G (n×3, columns M, A′, c), unknowns Y = (M, A′, c): M the north reading α_N (tracking
/// runs) or the zero position, A′ the amplitude α_0 (signed: A′ > 0 when r_2 > r_1 about M,
/// i.e. even readings lie above the centre), c the damping term. Residuals v = G·Ŷ − L.
///
/// Units. The input is SI: circle readings of a tracking run in radians, scale readings of a
/// zero-position run in divisions (StochasticInput::kind says which; they are not angles). The
/// models are fitted in the series' fitted unit (fitted_unit): circle readings in arc-seconds
/// relative to a reference reading (StochasticResult::reference_rad, the first reading unwrapped
/// and rounded down to a whole degree), scale readings in divisions. Every value of a
/// StochasticResult — M (relative to the reference), A′, c, σ, the residuals — is in that unit,
/// and so are the likelihoods: the REML log-likelihood of a series depends on the unit of its
/// readings (ℓ changes by −(n − 3)·ln s when they are scaled by s), so ℓ, AIC and BIC are stated,
/// and compare between models, in the fitted unit of the series.
///
/// Stochastic models compared (D = D(L)):
/// * white noise (ordinary least squares): D = σ_1²·I;
/// * C-type covariance functions: the shape fitted to the empirical autocovariance of the OLS
///   residuals ĉ_k = Σ_i v_i·v_{i+k}/n: exponential e^{−k/b}, Gaussian e^{−(k/b)²}, damped
///   cosine (second-order Markov) e^{−k/b}·cos(ω·k), giving the correlation matrix
///   R_ij = f(|i − j|); the amplitude a is then the REML estimate at that shape,
///   a = v_Rᵀ·R⁻¹·v_R/(n − 3) with v_R the GLS residuals under R (the spec leaves the amplitude
///   open; the LS fit of a·f to ĉ_k carries the 1/n of ĉ_k and no allowance for the 3
///   unknowns, so its σ are optimistic by √((n−3)/n)); D = a·R. Lags k < n/2 are used; the
///   damped cosine (3 parameters) is left out with a note below 5 lags (n < 10);
/// * Markov-1 and Markov-2 (markov_covariance.hpp), D = σ_1²·C·Cᵀ + σ_2²·B·Bᵀ, with ρ chosen
///   on the classical grid (ρ = 0.1 … 0.9; ρ_1, ρ_2 ∈ {−0.9, −0.8, …, 0.9} inside the AR(2)
///   triangle) and by maximising the restricted likelihood (profile over the variance
///   components: at every trial ρ their maximum is found in closed form,
///   adjust::maximise_two_component_reml).
/// At the chosen ρ of every Markov model σ_1², σ_2² are then estimated by variance-component
/// estimation started at that maximum (adjust::estimate_variance_components; a negative
/// estimate is clipped to 0 and said); where scoring does not settle in 100 iterations the
/// closed-form maximum is kept, its covariance from the inverse REML Fisher information, with a
/// note.
///
/// Degenerate fits: a model (other than white noise) is marked degenerate, with the reason, when
/// σ_1 is clipped to 0 or below kDegenerateSigma1Ratio × the white-noise σ_1 (the readings are
/// fitted almost exactly through the signal term; the restricted likelihood is unbounded
/// there) or below kDegenerateBookedRatio × the booked σ of one reading (when one is booked:
/// the signal term then fits the readings better than they can be read), when its ρ lies at the stationarity edge (Markov-1 |ρ| ≥ kStationarityEdge;
/// Markov-2 a root of z² − ρ_1·z − ρ_2 of modulus ≥ kStationarityEdge: a random walk that the
/// short series cannot tell from the functional model), or when its M or A′ differs from the
/// white-noise estimate by more than kDegenerateShift × the white-noise σ_1. A degenerate model
/// is reported but never recommended, never used in a likelihood-ratio test and never the
/// source of the signal used for the other models' influence.
///
/// Comparison: the REML log-likelihood ℓ (all models share G, so REML likelihoods compare);
/// AIC = −2ℓ + 2k, BIC = −2ℓ + k·ln(n − 3), k the number of covariance parameters (white 1;
/// exponential, Gaussian 2; damped cosine 3; Markov-1 3; Markov-2 4). The recommended model
/// is the non-degenerate one of smallest BIC (on a tie the one with fewer parameters). Likelihood-ratio
/// tests: white noise against Markov-1 (ML; 2 degrees of freedom — σ_2 is not identified at
/// ρ = 0, so the χ² reference is approximate) and Markov-1 against Markov-2 (ML; 1 degree of
/// freedom, ρ_2 = 0), at α = 5 %.
///
/// Signal influence (spec §4): for a Markov model X̂ = σ_2²·Bᵀ·D⁻¹·(L − G·Ŷ) and
/// ΔŶ = (GᵀD⁻¹G)⁻¹·GᵀD⁻¹·B·X̂. For white noise and the covariance-function models, which have
/// no signal term of their own, ΔŶ is their estimator applied to the signal B·X̂ predicted by
/// the non-degenerate Markov model of maximum likelihood with the smaller BIC (else the
/// non-degenerate grid model with the smaller BIC; else not stated, NaN) — how much of that
/// signal each model lets into M and A′.
///
/// Checks of the series (StochasticResult::warnings): the white-noise σ_1 against the booked σ
/// of one reading (StochasticInput::booked_sigma) by the global test of gyro reduce
/// (reversal.hpp, α = kReadingSigmaTestAlpha; above kBookingErrorRatio × the booked σ the
/// warning asks "booking error?"); and the length of the series against the
/// linearisation of (R1) in (R2): with κ̂, Â of an unweighted least-squares fit of (R1) itself
/// (M, A linear; κ by golden section on [0, 3·2ĉ/Â′] of the white-noise fit, whose own κ is
/// biased by the misfit), the neglected term q_i = (−1)^i·Â·(e^{−iκ̂} − 1 + iκ̂) ≈
/// (−1)^i·Â·κ̂²·i²/2, less its least-squares
/// projection on G, has an rms (r2_misfit_rms) that is compared with the white-noise σ_1
/// (warning above kR2MisfitRatio × σ_1: the Markov and C-type models then model the misfit).
/// The (R2) check is skipped (r2_misfit_rms = 0) after a "booking error?" warning.
///
/// Standard deviations: D_Ŷ = (GᵀD⁻¹G)⁻¹ with D at the estimated components (not rescaled).
/// σ of ρ and of the components of the ML models from the inverse REML Fisher information over
/// (ρ…, σ_1², σ_2²) (∂D/∂ρ by central differences); of the grid models from the VCE alone.
/// σ(σ_k) = σ(σ_k²)/(2σ_k).
///
/// Sources: Grafarend & Kleusberg (gyro VCE); Teunissen & Amiri-Simkooei (2008) J Geod
/// 82:65–82; Harville (1977) JASA 72:320–338; Akaike (1974), Schwarz (1978).

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "meridian/adjust/variance_components.hpp"
#include "meridian/core/progress.hpp"
#include "meridian/core/uncertain.hpp"

namespace meridian::gyro {

enum class StochasticModel {
  WhiteNoise,    ///< ordinary least squares, D = σ_1²·I
  Exponential,   ///< C-type: a·e^{−k/b}
  Gaussian,      ///< C-type: a·e^{−(k/b)²}
  DampedCosine,  ///< C-type: a·e^{−k/b}·cos(ω·k)
  Markov1Grid,   ///< Markov-1, ρ from the grid 0.1 … 0.9
  Markov2Grid,   ///< Markov-2, (ρ_1, ρ_2) from the grid on [−0.9, 0.9]²
  Markov1Ml,     ///< Markov-1, ρ by maximum restricted likelihood
  Markov2Ml,     ///< Markov-2, (ρ_1, ρ_2) by maximum restricted likelihood
};

/// "white-noise", "c-exponential", "c-gaussian", "c-damped-cosine", "markov1-grid",
/// "markov2-grid", "markov1-ml", "markov2-ml".
std::string to_string(StochasticModel m);

/// How the GLS is computed (both give the same numbers to rounding; spec §5).
enum class GlsRoute {
  Whitening,        ///< L⁻¹·G, L⁻¹·L with D = L·Lᵀ and a QR (adjust::solve_linear)
  NormalEquations,  ///< GᵀD⁻¹G and GᵀD⁻¹L with D⁻¹ applied by Cholesky solves
};

struct StochasticOptions {
  adjust::VceMethod vce_method = adjust::VceMethod::LsVce;
  GlsRoute route = GlsRoute::Whitening;
  bool covariance_functions = true;  ///< include the C-type models
  bool markov2 = true;               ///< include the Markov-2 models (grid and ML)
};

/// What the readings of a series are (and so the unit its models are fitted in).
enum class SeriesKind {
  Circle,  ///< circle readings at the reversal points of a tracking run: angles, radians
  Scale,   ///< scale readings at the reversal points of a zero-position run: divisions, not angles
};

/// The unit of a StochasticResult's values for a series of this kind: "arcsec" (Circle, relative
/// to StochasticResult::reference_rad), "div" (Scale). Used in messages and by the writers.
std::string fitted_unit(SeriesKind kind);

/// One reversal-point series.
struct StochasticInput {
  SeriesKind kind = SeriesKind::Circle;
  /// r_1 … r_n (n ≥ 6: 3 unknowns, 2 components, +1). Circle: circle readings in radians, in any
  /// turn (readings across 0°/360° are unwrapped, unwrap_circle_readings); Scale: scale readings
  /// in div.
  std::vector<double> readings;
  /// The booked a-priori σ of one reading: radians (Circle) or div (Scale); NaN or ≤ 0: none
  /// booked.
  double booked_sigma = std::numeric_limits<double>::quiet_NaN();
  StochasticOptions options;
};

/// Thresholds of the degeneracy checks and the series checks (see the file comment).
inline constexpr double kDegenerateSigma1Ratio = 1e-2;
inline constexpr double kDegenerateBookedRatio = 0.2;
inline constexpr double kStationarityEdge = 0.97;
inline constexpr double kDegenerateShift = 10.0;
inline constexpr double kR2MisfitRatio = 0.25;
/// σ_1 of white noise more than this times the booked σ: the warning asks "booking error?"
/// (below it, a rejected test says the readings scatter more than booked).
inline constexpr double kBookingErrorRatio = 10.0;
/// m_M of a model more than this times the white-noise m_M: degenerate (the model explains the
/// readings by a correlation so strong that the centre is hardly determined).
inline constexpr double kDegenerateSigmaNorthRatio = 3.0;
/// A correlated model is recommended only when its AICc is lower than white noise's by at least
/// this much ("clearly better"; Burnham & Anderson 2002: a difference below 4 leaves the simpler
/// model well supported).
inline constexpr double kClearlyBetterAicc = 4.0;
/// Data snooping of the readings (white noise, σ from the other readings): α0 per reading.
inline constexpr double kSnoopingAlpha0 = 1e-3;

/// The minimum series length n at which a model of this family may be recommended (see
/// docs/gyro-stochastic.md, "Recommendation", for the Monte Carlo behind them). White noise: 6.
int minimum_readings_to_recommend(StochasticModel m);

/// Student's t_{0.975}(n − 3): the factor of m_M for the 95 % interval of the centre of a series
/// of n readings (n ≥ 4).
double interval95_factor(int readings);

/// Options of the GLS of (R1) (reversal_gls_nonlinear).
struct R1GlsOptions {
  /// Maximum Gauss–Newton steps (adjust::NonlinearOptions::max_iterations), ≥ 1.
  int max_iterations = 50;
  /// Converged when every |ΔY_j| ≤ step_tolerance·(|Y_j| + s_j), s = (|M₀| + |A₀|, |A₀|, 1)
  /// from the start (adjust::NonlinearOptions::step_tolerance), > 0.
  double step_tolerance = 1e-12;
};

/// The GLS of the non-linear reversal-point model (R1) of gyro-theodolite.md §3,
///     r_i = M + (−1)^i·A·e^{−iκ},   i = 1 … n,
/// with a full covariance D of the readings. Values in the unit of the readings (arcsec or div);
/// κ is the decay per half period (dimensionless, per reading; κ > 0 for a decaying
/// oscillation). A is signed as A′ of (R2): A > 0 when the even readings lie above the centre.
struct R1GlsFit {
  Eigen::Vector3d y = Eigen::Vector3d::Zero();  ///< Ŷ = (M, A, κ)
  /// D_Ŷ = (JᵀD⁻¹J)⁻¹, J = ∂f/∂Y at Ŷ (the a-priori covariance at the given D, not rescaled
  /// by σ̂0 — as the (R2) GLS of the models).
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  Uncertain centre;     ///< M and sqrt(D_Ŷ(0,0)): α_N (tracking) or the zero position
  Uncertain amplitude;  ///< A and sqrt(D_Ŷ(1,1))
  Uncertain decay;      ///< κ and sqrt(D_Ŷ(2,2))
  Eigen::Vector3d start = Eigen::Vector3d::Zero();  ///< (M₀, A₀, κ₀) from the OLS of (R2)
  Eigen::VectorXd residuals;  ///< v = f(Ŷ) − L
  double vtpv = 0.0;          ///< vᵀD⁻¹v
  int iterations = 0;         ///< Gauss–Newton steps taken
  bool converged = false;     ///< always true when returned (non-convergence throws)
};

/// One model's fit. Values in the series' fitted unit; NaN where a quantity does not apply.
struct ModelFit {
  StochasticModel model = StochasticModel::WhiteNoise;
  Uncertain north;      ///< M (α_N or zero position) and m_M
  Uncertain amplitude;  ///< A′ (α_0) and its σ
  Uncertain damping;    ///< c and its σ
  /// Markov-1: (ρ); Markov-2: (ρ_1, ρ_2). Empty for white noise and the C-type models.
  std::vector<double> rho;
  std::vector<double> rho_sigma;  ///< σ of rho (ML models; NaN otherwise)
  /// C-type shape parameters: exponential, Gaussian (b) in lags; damped cosine (b, ω) with ω in
  /// rad per lag. Empty for the other models.
  std::vector<double> shape;
  /// σ_1 (noise; for white noise the σ of one reading; for C-type √a) and its σ (white noise
  /// and C-type: σ_1/√(2(n − 3)), the REML σ at fixed shape).
  Uncertain sigma1;
  Uncertain sigma2;  ///< σ_2 (signal; Markov models) and its σ; NaN otherwise
  /// ΔŶ = (ΔM, ΔA′, Δc); NaN when no non-degenerate Markov model supplies the signal.
  Eigen::Vector3d signal_influence = Eigen::Vector3d::Zero();
  double log_likelihood = 0.0;                                 ///< REML ℓ
  double aic = 0.0;
  double bic = 0.0;
  /// AICc = AIC + 2k(k + 1)/(r − k − 1), r = n − 3 (the number of error contrasts of REML;
  /// Hurvich & Tsai 1989); +∞ when r − k − 1 ≤ 0 (too few readings for k parameters).
  double aicc = 0.0;
  int covariance_parameters = 0;  ///< k (grid values of ρ and shape parameters counted)
  /// VCE iterations at the chosen ρ (0 for models without VCE, and for a Markov model whose
  /// VCE did not settle and whose components are the closed-form maximum: see notes).
  int vce_iterations = 0;
  bool recommended = false;
  /// The fit is at the edge of its parameter space (see the file comment); reason says how.
  bool degenerate = false;
  std::string degenerate_reason;
  /// D_{i,i+k}/sqrt(D_ii·D_{i+k,i+k}) averaged over i, k = 0 … n−1.
  std::vector<double> implied_autocorrelation;
  /// The GLS of the non-linear model (R1) with this model's D (reversal_gls_nonlinear); none
  /// when it could not be computed (the reason is then in notes, starting "(R1) GLS").
  std::optional<R1GlsFit> r1;
  std::vector<std::string> notes;
};

struct LikelihoodRatioTest {
  StochasticModel null_model = StochasticModel::WhiteNoise;
  StochasticModel alternative = StochasticModel::Markov1Ml;
  double statistic = 0.0;  ///< 2·(ℓ_alt − ℓ_null), ≥ 0 up to rounding
  int dof = 0;
  double p_value = 1.0;
  bool rejected = false;  ///< the null model is rejected at α = 5 %
};

/// A reading located by data snooping (adjust::iterated_data_snooping of the white-noise fit of
/// (R2), σ from the other readings, α0 = kSnoopingAlpha0).
struct ReadingOutlier {
  int reading = 0;    ///< 1-based index i of r_i
  double w = 0.0;     ///< Baarda's w at unit variance factor
  double t = 0.0;     ///< t = w/σ̂_(i), ~t(dof − 1)
  double critical = 0.0;  ///< t_{1−α0/2}(dof − 1)
  int dof = 0;
  Uncertain error;    ///< estimated error of r_i (fitted unit; > 0: r_i too large)
};

/// The white-noise fit with the located outliers left out (each given its own unknown, which is
/// the same as deleting it for independent readings; the index i of the others is kept).
struct OutlierFreeFit {
  Uncertain north;   ///< M and m_M (a-posteriori: σ̂0 of the remaining readings)
  Uncertain amplitude;
  double sigma1 = 0.0;  ///< σ̂ of one reading from the remaining readings
  int readings_used = 0;
  int dof = 0;
};

struct StochasticResult {
  SeriesKind kind = SeriesKind::Circle;  ///< of the input; fixes the fitted unit (fitted_unit)
  /// Circle: the reading the series is fitted relative to (radians: the first reading, unwrapped,
  /// rounded down to a whole degree); a centre M of the result is the reading reference_rad + M″.
  /// 0 for Scale.
  double reference_rad = 0.0;
  int readings = 0;
  /// r_1 … r_n as fitted, in the fitted unit (arcsec relative to reference_rad, or div).
  std::vector<double> fitted_readings;
  /// The booked σ of one reading in the fitted unit (NaN when none was booked).
  double booked_sigma = std::numeric_limits<double>::quiet_NaN();
  std::vector<ModelFit>
      models;           ///< in the order of StochasticModel (models that fail are left out)
  int recommended = 0;  ///< index into models
  std::vector<LikelihoodRatioTest> tests;
  Eigen::VectorXd ols_residuals;  ///< v of the white-noise fit
  /// Empirical autocorrelation ĉ_k/ĉ_0 of the OLS residuals, k = 0 … n−1.
  std::vector<double> residual_autocorrelation;
  /// Profile REML of Markov-2 on the grid (maximised over σ_1², σ_2² at each point):
  /// rho1_grid × rho2_grid, NaN outside the triangle or where the likelihood has no maximum with
  /// σ_1² > 0 (the covariance would be singular).
  std::vector<double> rho1_grid, rho2_grid;
  Eigen::MatrixXd markov2_surface;
  /// rms of the part of (R1) that (R2) cannot represent, at the fitted decay (fitted unit;
  /// 0 when the fitted decay is not positive).
  double r2_misfit_rms = 0.0;
  std::vector<std::string> notes;
  /// Readings located by data snooping, in the order located (empty: none).
  std::vector<ReadingOutlier> outliers;
  /// The white-noise fit without them (set when outliers is not empty).
  std::optional<OutlierFreeFit> without_outliers;
  /// Why the recommended model is recommended, one line.
  std::string recommendation_reason;
  /// The centre to use and its σ (fitted unit): the recommended model's, or white noise's
  /// without the outliers; for white noise its σ is the largest of the OLS σ and the σ the OLS
  /// centre has under the covariance D of every non-degenerate correlated model,
  /// sqrt([(GᵀG)⁻¹GᵀDG(GᵀG)⁻¹]_00) (a correlation the comparison cannot confirm is not ruled
  /// out either).
  Uncertain answer;
  /// The 95 % half-width of answer: t_{0.975}(dof)·σ, dof = readings used − 3.
  double answer_half95 = 0.0;
  /// What answer's σ rests on, one phrase.
  std::string answer_basis;
  /// Findings about the series itself: σ_1 far above the booked σ, (R2) too short-sighted.
  std::vector<std::string> warnings;

  /// The fit of model m; throws InputError when it is not in models.
  const ModelFit& fit(StochasticModel m) const;
};

/// Fit and compare the models for one series (in its fitted unit, see the file comment). Throws
/// InputError when n < 6 (3 unknowns and 2 variance components + 1), a reading is not finite
/// (field "readings[i]"), or the series has no scatter (all residuals of OLS zero);
/// NumericalError when no Markov model could be fitted. Individual
/// models that fail (covariance not positive definite, VCE not converging) are left out with a
/// note in StochasticResult::notes. Results never contain NaN in M, A′ or their σ.
StochasticResult analyse_stochastic(const StochasticInput& input, Progress* progress = nullptr);

/// The GLS of (R2) with a given covariance D (n×n, positive definite, else NumericalError):
/// Ŷ and D_Ŷ by the chosen route. Throws InputError when sizes differ or n < 4.
struct GlsFit {
  Eigen::Vector3d y;
  Eigen::Matrix3d covariance;
  Eigen::VectorXd residuals;  ///< v = G·Ŷ − L
};
GlsFit reversal_gls(const std::vector<double>& readings, const Eigen::MatrixXd& D,
                    GlsRoute route = GlsRoute::Whitening);

/// The design G of (R2) for n readings (n×3).
Eigen::MatrixXd reversal_design(int n);

/// Fit (R1) by Gauss–Newton on the whitened system L⁻¹(f(Y) − l), D = L·Lᵀ (Cholesky; no inverse
/// of D), with adjust::solve_nonlinear (its Levenberg–Marquardt safeguard damps a step only when
/// the full step would raise vᵀD⁻¹v; near the minimum the steps are Gauss–Newton's) and the
/// analytic Jacobian ∂f_i/∂M = 1, ∂f_i/∂A = (−1)^i·e^{−iκ}, ∂f_i/∂κ = −(−1)^i·i·A·e^{−iκ}.
/// Start: the unweighted least squares of (R2), (M′, A′, c), mapped by matching (R2) to the
/// first-order expansion of (R1): M₀ = M′, A₀ = A′ + c, κ₀ = 2c/A₀.
/// Requires n ≥ 4 readings (3 unknowns + 1), D n×n symmetric positive definite.
/// Throws InputError when n < 4, sizes differ, a reading or D is not finite (field "readings[i]"
/// or "covariance"), or the options are invalid; NumericalError when D is not positive definite,
/// |A₀| ≤ 1e-12·max|r_i| (no oscillation; κ is then not determined), the normal matrix is singular, Gauss–Newton
/// does not converge within max_iterations, or the solution or its σ is not finite. The message
/// starts with "(R1) GLS:". Never returns NaN.
R1GlsFit reversal_gls_nonlinear(const std::vector<double>& readings, const Eigen::MatrixXd& D,
                                const R1GlsOptions& options = {});

}  // namespace meridian::gyro
