#pragma once
/// \file reduce.hpp
/// The `maglev reduce` workflow: one two-position determination of a
/// magnetically suspended gyro from its rotor-current series (maglev-gyro
/// spec §1, §3) to α_1, gyro north N_G and the bias b̂, with σ, the segments
/// kept and rejected per position, and the plain, median and Huber results
/// beside the processed one.
///
///   ReduceInput (io::maglev_reduce_input and the series readers) → process()
///   → ReduceResult → report::maglev_reduce_text / maglev_reduce_to_json /
///   maglev_reduce_document. The runner io::run_maglev_reduce_files does all
///   of it for files; the Result carries what its writers show (the constants
///   and options used, each position's series).
///
/// Processing of each position (options.process):
///  1. stationarity.hpp: segments, mean and autocovariance tests, stable
///     segments kept;
///  2. wavelet denoising (denoise.hpp) of every run of consecutive kept
///     segments on its own (a run too short for the level gets the deepest
///     level it allows; a run too short for level 1 is used as it is);
///  3. the mean of the cleaned kept samples. Its σ is that of the kept raw
///     samples taken as one series (series_statistics.hpp, effective sample
///     size; the same estimator as for all samples, so the same samples give
///     the same σ): denoising removes high-frequency noise but not the
///     low-frequency part that limits a mean, so it does not make the mean
///     more precise. A warning when the correlation time exceeds a tenth of
///     the segment length (the segment tests are then approximate).
/// Without processing, every sample is kept and used raw.
/// Then model.hpp: α_1 = asin((Ī_1 − Ī_2)/(2A)), N_G = r_1 − α_1, b̂.
///
/// Symmetry check (spec §3 step 4), when a prior bias b₀ (σ) is given — from
/// a calibration (its constant deviation I*) or the instrument: the two
/// positions must lie symmetrically about it, z = (Ī_1 + Ī_2 − 2·b₀)/
/// sqrt(σ²(Ī_1) + σ²(Ī_2) + 4σ²(b₀)), two-sided normal test at α; a failure is
/// a warning (one position still disturbed, or the bias has changed).
///
/// Azimuth chain: with a target reading, the gyro azimuth A_G = r_T − N_G and
/// gyro::azimuth_chain (instrument constant E, Laplace, convergence).
///
/// Errors (field paths, which the runner's io::SourceMap turns into file:line:
/// column): InputError for an empty or constant series ("position1.current_A"),
/// non-monotonic time ("position2.time_s[17]"), non-finite samples, times and
/// currents of different lengths (series.hpp), too few samples for the
/// segments and bad options ("position1.segment_length"); NumericalError for
/// no stable segment ("position1") or |(Ī_1 − Ī_2)/(2A)| > 1 ("alpha1"); InputError for
/// the same series at both positions ("position2.current_A": the same file given twice).
///
/// Plausibility (issue 30): the currents' sample-to-sample noise as an angle of A below 0.5″
/// means they are probably 10³ too small for K (values in A under an [mA] header): a warning
/// starting "UNIT SLIP?" and ReduceResult::unit_slip_suspected.

#include <optional>
#include <string>
#include <vector>

#include "meridian/core/progress.hpp"
#include "meridian/core/uncertain.hpp"
#include "meridian/gyro/azimuth_chain.hpp"
#include "meridian/maglev/denoise.hpp"
#include "meridian/maglev/drift.hpp"
#include "meridian/maglev/model.hpp"
#include "meridian/maglev/series.hpp"
#include "meridian/maglev/series_statistics.hpp"
#include "meridian/maglev/settling.hpp"
#include "meridian/maglev/stationarity.hpp"

namespace meridian::maglev {

struct ReduceOptions {
  bool process = true;  ///< stationarity tests and denoising; false: plain means of all samples
  StationarityOptions stationarity;
  bool denoise = true;  ///< wavelet denoising of the kept runs (when process)
  DenoiseOptions denoising{.wavelet_order = 4, .level = kDefaultLevel};
  double huber_k = 1.345;  ///< tuning of the Huber mean (units of the MAD scale)
  /// Prior bias b₀ for the symmetry check (e.g. I* of a calibration), A.
  std::optional<Uncertain> prior_bias_A;
  /// Common drift on the positions' clock (drift.hpp), fitted jointly with the levels when the
  /// positions share one clock; none: each position's mean on its own (a drift then biases α_1).
  DriftModel drift = DriftModel::linear;
  /// The settling cut at the start of every block (settling.hpp), when processing.
  SettlingOptions settling;
};

/// What turns N_G into a target azimuth (optional).
struct ChainSetup {
  Uncertain target_reading_rad;       ///< r_T, circle reading of the target
  Uncertain instrument_constant_rad;  ///< E
  std::optional<Uncertain> eta_rad;   ///< η at the station
  double convergence_rad = 0.0;       ///< γ
};

struct ReduceInput {
  std::string source;             ///< what the series are, for reports (their files); may be empty
  Uncertain scale_A_s_per_rad;    ///< K
  double latitude_rad = 0.0;      ///< φ
  Uncertain circle_reading1_rad;  ///< r_1 (spin-axis circle reading at position 1)
  PositionSeries position1, position2;
  std::optional<ChainSetup> chain;
  ReduceOptions options;
};

/// One position: its series and its statistics before and after processing.
struct PositionResult {
  PositionSeries series;  ///< as given (times of the segments, the raw samples)
  std::size_t samples = 0;
  MeanEstimate raw;                                ///< all samples, unprocessed
  std::optional<StationarityResult> stationarity;  ///< when processed
  std::size_t kept_samples = 0;
  MeanEstimate kept;                 ///< the kept raw samples
  Uncertain cleaned_mean_A;          ///< mean of the cleaned kept samples, σ of `kept`
  double median_A = 0.0;             ///< of the kept raw samples
  Uncertain huber_A;                 ///< of the kept raw samples
  std::string huber_failed;          ///< why the Huber mean failed (empty: it did not)
  double variance_raw_A2 = 0.0;      ///< of all raw samples
  double variance_cleaned_A2 = 0.0;  ///< of the cleaned kept samples
  std::vector<double> cleaned_A;     ///< same length as the series; raw where not kept
  std::vector<char> kept_mask;       ///< 1 where the sample was kept
  std::vector<int> denoise_levels;   ///< level used per kept run (0: run not denoised)
  double noise_sigma_A = 0.0;        ///< wavelet noise σ (of the longest run)
};

/// The common drift of a determination (drift.hpp), when fitted.
struct DriftResult {
  DriftModel model = DriftModel::linear;  ///< as fitted
  std::string sequence;                   ///< the blocks' positions in time order, "1-2-1"
  std::vector<TimeBlock> blocks;
  double reference_time_s = 0.0;          ///< t_ref: the levels and b̂ are at this time
  Uncertain rate_A_per_s;                 ///< drift rate at t_ref
  std::optional<Uncertain> curvature_A_per_s2;  ///< second derivative (quadratic model)
  double z = 0.0, p = 1.0;                ///< test of the rate against 0 (normal, two-sided)
  bool significant = false;               ///< p < α
  double sigma_inflation = 1.0;           ///< σ(α_1) with / without the drift fitted (sqrt VIF)
  bool separable = true;                  ///< sigma_inflation ≤ 3
  double alpha1_correction_rad = 0.0;     ///< α_1 with the drift − α_1 from the levels alone
  double long_run_variance_A2 = 0.0;      ///< σ²_LR of the residuals
  double n_eff = 0.0;                     ///< effective samples of the residuals
  /// Linear model only: z of a quadratic term fitted as a check (|z| large: not linear).
  std::optional<double> curvature_check_z;
};

struct ReduceResult {
  // What was reduced (ReduceInput), for the writers.
  std::string source;            ///< ReduceInput::source
  Uncertain scale_A_s_per_rad;   ///< K
  double latitude_rad = 0.0;     ///< φ
  ReduceOptions options;         ///< as given (denoising.level as asked; PositionResult::denoise_levels as used)

  Uncertain amplitude_A;  ///< A = K·ω_e·cos φ
  PositionResult position1, position2;
  TwoPositionSolution processed;  ///< from the cleaned kept means (= plain without processing)
  TwoPositionSolution plain;      ///< from the means of all raw samples
  std::optional<TwoPositionSolution> median;  ///< from the medians (σ of the kept means ×√(π/2))
  std::optional<TwoPositionSolution> huber;
  struct Symmetry {
    double z = 0.0, p = 0.0;
    bool passed = true;
  };
  std::optional<Symmetry> symmetry;
  std::optional<DriftResult> drift;  ///< when a drift was fitted
  std::vector<SettlingCut> settling;  ///< the blocks whose start was cut
  std::optional<gyro::AzimuthChainResult> chain;
  std::vector<std::string> notes, warnings;
  /// Plausibility of the currents' scale (issue 30): the larger sample-to-sample noise of the
  /// two positions as an angle, σ_i / (K·ω_e·cos φ) (rad; 0 when not computed), and whether
  /// it is so small (< 0.5″) that the currents are probably 10³ off their unit.
  double sample_noise_rad{};
  bool unit_slip_suspected{};
};

/// Process one determination (see the file comment).
ReduceResult process(const ReduceInput& in, Progress* progress = nullptr);

}  // namespace meridian::maglev
