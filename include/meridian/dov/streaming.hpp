#pragma once
/// \file streaming.hpp
/// The deflection workflow over a line of any length with flat memory: samples come from a
/// SampleSource a chunk at a time into the filter's forward pass, and every epoch's result
/// goes to an EpochSink in time order after the smoother. This is the one implementation of
/// the workflow; dov::process(const Input&) (deflection.hpp) runs it over vectors.
///
/// Three passes, each streaming (docs/deflection.md, "Memory"):
///  1. forward: checks, predict, update (deflection.hpp, steps 1–5) per sample; the filter's
///     records go to filter::SmootherStorage and the epoch's own outputs (time, position, model
///     values, ΔΦ, filtered estimate, innovations, truth) to a record store beside it, both
///     spilling to anonymous temporary files beyond Options::storage.memory_limit_bytes —
///     without pass 3 only what the smoothed statistics need (η_G, ξ_G and the truth; nothing
///     for a line without truth);
///  2. backward: the RTS smoother (filter/rts_smoother.hpp), last epoch first, joined with
///     the stored outputs of each epoch; the completed epoch results go to a third store;
///  3. the completed results, read back in time order, to the sink and the epochs the Result
///     keeps (skipped when neither is asked for).
/// Memory is O(chunk + buffers + kept epochs), independent of the line length — except a
/// stationary start and the first minutes of motion: the initial σ of x_E, x_N needs the
/// reference speed (deflection.hpp, Options::reference_speed_window_s), so samples are held
/// until Options::reference_speed_window_s (300 s) after the carrier first moves
/// (≈ 200 bytes each; 30 000 at 100 Hz) or the line ends. Disk: 424 + 2 × 304 bytes
/// per epoch in the temporary files beyond the memory limit with pass 3; without it 424 + 32
/// (with truth; 96 more with true states, 0 without truth).
///
/// Errors: as dov::process (deflection.hpp); errors of the source propagate unchanged.

#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "meridian/core/progress.hpp"
#include "meridian/dov/deflection.hpp"

namespace meridian::dov {

/// Where the samples of a line come from, in time order (io/dov_jobs.hpp: a line file).
class SampleSource {
 public:
  virtual ~SampleSource() = default;
  /// Replace the contents of `samples` (and of `truth`, one per sample when has_truth(), else
  /// left empty) by the next up to `max` (≥ 1) samples; return their number, 0 at the end.
  virtual std::size_t next(std::vector<Sample>& samples, std::vector<Truth>& truth,
                           std::size_t max) = 0;
  /// Whether the line carries truth (fixed for the whole line).
  virtual bool has_truth() const = 0;
  /// The number of samples if known in advance (for progress), else nullopt.
  virtual std::optional<std::size_t> size_hint() const { return std::nullopt; }
  /// Where the samples come from (Result::origin).
  virtual Origin origin() const { return {}; }
  /// What the source itself has to say, asked once the line has been read: notes (e.g. the
  /// gravity model that gave η_G, ξ_G) and warnings (e.g. columns of a file that were not
  /// read), after the workflow's own in Result::notes and Result::warnings.
  virtual std::vector<std::string> notes() const { return {}; }
  virtual std::vector<std::string> warnings() const { return {}; }
};

/// Receives each epoch's result, in time order (epoch 0 first).
using EpochSink = std::function<void(const EpochResult&)>;

/// EpochOutputs::keep_epochs: every epoch.
inline constexpr std::size_t kAllEpochs = std::numeric_limits<std::size_t>::max();

/// Where the epochs of a streamed line go besides the summary.
struct EpochOutputs {
  /// Each epoch's result, in time order (may be empty).
  EpochSink sink;
  /// Result::epochs: 0 none, kAllEpochs every epoch (dov::process), n > 0 at most n of them:
  /// every k-th epoch with k = 1, 2, 4, … doubled (and the kept ones halved) whenever more
  /// than n would be held, so memory stays bounded for a line of any length (a report draws
  /// them; Result::epoch_stride = k).
  std::size_t keep_epochs = 0;
};

/// Filter and smooth the line of `source` with `options` (validated first), handing the epochs
/// to `outputs`. The Result carries the options, source.origin(), the summary, notes and
/// warnings (the source's after the workflow's) and the kept epochs. Without a sink and kept
/// epochs the third pass is skipped. Throws as dov::process.
Result process_stream(SampleSource& source, const Options& options,
                      const EpochOutputs& outputs = {}, Progress* progress = nullptr);

}  // namespace meridian::dov
