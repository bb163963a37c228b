#pragma once
/// \file stochastic_book.hpp
/// The `gyro stochastic` workflow: every reversal-point series of one field book — each tracking
/// determination's circle readings, each zero-position run's scale readings — analysed under the
/// competing stochastic models (analyse_stochastic, stochastic.hpp).
///
///   ReduceInput | CampaignInput (io::read_gyro_reduce_file | read_campaign_file)
///   → stochastic_book() → StochasticBookInput → process() → StochasticBookResult
///   → report::stochastic_text / stochastic_to_json / stochastic_document
///
/// The runner is io::run_stochastic_file (io/gyro_jobs.hpp).

#include <string>
#include <vector>

#include "meridian/core/progress.hpp"
#include "meridian/gyro/campaign.hpp"
#include "meridian/gyro/reduce.hpp"
#include "meridian/gyro/stochastic.hpp"

namespace meridian::gyro {

/// The fewest readings a series of a book needs to be analysed (3 unknowns M, A′, c, 2 variance
/// components and 1 more); shorter series are counted but not analysed.
inline constexpr std::size_t kMinStochasticSeries = 6;

/// One reversal-point series of a field book.
struct BookSeries {
  /// Field path of the series in the book's Input: "determinations[0].reversals",
  /// "line.determinations[1].zero_before", "known_line.after[0].zero_after".
  std::string field;
  std::string label;  ///< the determination's label as booked (may be empty)
  /// Tracking: the circle readings (radians) with the determination's booked reading σ
  /// (sigma_reading_rad); zero position: the scale readings (div) with the instrument's
  /// sigma_reading_div.
  StochasticInput input;
};

/// The series of one field book, in the book's order: per determination its tracking reversals,
/// then its zero-position runs before and after.
struct StochasticBookInput {
  /// The book's name as given (for the writers; never opened here).
  std::string file;
  /// A campaign file: series from known_line.before, known_line.after and line.determinations.
  bool campaign = false;
  std::vector<BookSeries> series;  ///< every series, short ones included
};

/// The series of a reduce book (field paths "determinations[i]…"). `file` is left empty.
StochasticBookInput stochastic_book(const ReduceInput& in);

/// The series of a campaign (known_line.before, known_line.after, line.determinations).
StochasticBookInput stochastic_book(const CampaignInput& in);

/// One analysed series of a field book.
struct StochasticSeries {
  /// BookSeries::field followed by the book's label in parentheses, if any.
  std::string label;
  StochasticResult result;  ///< kind, reference, fitted readings and every model (stochastic.hpp)
};

/// Every series of one field book with at least kMinStochasticSeries readings, in the book's order.
struct StochasticBookResult {
  std::string file;       ///< StochasticBookInput::file
  bool campaign = false;  ///< StochasticBookInput::campaign
  std::vector<StochasticSeries> series;
};

/// Analyse every series of at least kMinStochasticSeries readings (analyse_stochastic, with
/// `progress`). Throws, for a series that cannot be analysed, its InputError/NumericalError with
/// the series' field ("determinations[2].reversals") unless the error names a field of its own;
/// and InputError at field "determinations" ("line.determinations" for a campaign) when no series
/// is long enough, saying how many series the book has and the longest (a standard programme of 5
/// reversals per run is below the minimum).
StochasticBookResult process(const StochasticBookInput& in, Progress* progress = nullptr);

}  // namespace meridian::gyro
