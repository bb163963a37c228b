#pragma once
/// \file stochastic_choice.hpp
/// The stochastic model of a tracking determination's reversal readings under which its north
/// reading N_G is computed (the campaign's `stochastic_model:` option), and the record of what
/// was used for one determination. The computation is gyro::with_stochastic_model
/// (stochastic_determination.hpp); the models are those of stochastic.hpp.

#include <limits>
#include <string>
#include <vector>

namespace meridian::gyro {

/// The model requested for the reversal readings of tracking determinations.
enum class StochasticChoice {
  White,        ///< independent readings: the reduction of `gyro reduce`, unchanged (default)
  Markov1,      ///< Markov-1 with ρ by maximum restricted likelihood ("markov1-ml")
  Markov2,      ///< Markov-2 with (ρ_1, ρ_2) by maximum restricted likelihood ("markov2-ml")
  Recommended,  ///< the model the comparison recommends for this series (smallest BIC)
};

/// "white", "markov1", "markov2", "recommended".
std::string to_string(StochasticChoice c);

/// Inverse of to_string. Throws InputError listing the accepted names.
StochasticChoice stochastic_choice_from_string(const std::string& name);

/// What gave a determination's N_G (DeterminationResult::stochastic).
struct StochasticUse {
  StochasticChoice requested = StochasticChoice::White;
  /// The model whose covariance D of the readings gave N_G: "white" (independent readings, the
  /// reduction of gyro reduce: σ from the booked reading σ or σ̂0, reversal.hpp) or a model name
  /// of stochastic.hpp ("markov1-ml", "markov2-ml", "c-exponential", …).
  std::string used = "white";
  /// The requested model could not be used (too few readings, not fitted, degenerate, method
  /// without a GLS, non-tracking run): white noise instead; `reason` says why and the
  /// determination has a warning.
  bool fallback = false;
  std::string reason;
  /// Parameters of the model used (empty / NaN for white): ρ (Markov-1), (ρ_1, ρ_2) (Markov-2),
  /// none for covariance functions; σ_1, σ_2 in arcsec (σ_2 NaN for covariance functions).
  std::vector<double> rho;
  double sigma1_arcsec = std::numeric_limits<double>::quiet_NaN();
  double sigma2_arcsec = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace meridian::gyro
