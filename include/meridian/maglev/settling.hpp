#pragma once
/// \file settling.hpp
/// The settling transient after each rotation (maglev-gyro spec §3a): cut the start of every
/// position block, by a duration given or found by an exponential fitted and tested.
///
/// Detection, per block of residuals r (the samples minus their position's level and the drift,
/// in time order, t from the block's first sample): for every τ of a grid (1, 2, 5, 10, 20, 50,
/// 100 s, below a third of the block) the least-squares fit r ≈ c + a·g, g = exp(−t/τ), gives
/// â = Σ(g − ḡ)(r − r̄)/Σ(g − ḡ)² with σ²(â) = σ²_LR/Σ(g − ḡ)² (σ²_LR the long-run variance of the
/// residuals: conservative for a regressor faster than the noise's correlation); z = â/σ(â), the
/// τ of the largest |z| taken. The transient is significant when its two-sided normal p-value is
/// below α/(G·B) (Bonferroni over the G values of τ and the B blocks). Its cut is the time after
/// which what is left of it biases the block's mean by less than a tenth of the level's σ:
/// cut = τ·ln(|â|·τ/(T·0.1·σ_μ)), T the block's duration, limited to [0, T/2] (a cut at T/2 is
/// reported as limited).
///
/// Units: s, A. Errors: none (a block shorter than 3 samples per τ is skipped).

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

namespace meridian::maglev {

struct SettlingOptions {
  std::optional<double> cut_s;  ///< a cut given (s from each block's start); unset: detect
  bool detect = true;           ///< detect when no cut is given
};

/// The settling cut of one block.
struct SettlingCut {
  int position = 1;
  double block_begin_s = 0.0;     ///< time of the block's first sample
  double cut_s = 0.0;             ///< samples before block_begin_s + cut_s are cut
  std::size_t samples_cut = 0;
  bool detected = false;          ///< from the exponential test (false: given)
  bool limited = false;           ///< the cut reached half the block
  double amplitude_A = 0.0, tau_s = 0.0, z = 0.0;  ///< the exponential fitted (detected)
};

/// The exponential test of one block (see the file comment): times and residuals of the block,
/// σ²_LR of the residuals per sample, σ of the position's level, the significance level per
/// test. Returns the cut when the transient is significant.
std::optional<SettlingCut> detect_settling(std::span<const double> time_s,
                                           std::span<const double> residual_A,
                                           double long_run_variance_A2, double level_sigma_A,
                                           double alpha_per_test);

/// The τ grid (s) for a block of `duration_s` and `samples`.
std::vector<double> settling_time_constants(double duration_s, std::size_t samples);

}  // namespace meridian::maglev
