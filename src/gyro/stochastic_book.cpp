#include "meridian/gyro/stochastic_book.hpp"

#include <algorithm>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::gyro {
namespace {

// Every series of the determinations `dets` (field prefix `prefix`: "determinations",
// "line.determinations", …), appended to `out`.
void add_series(std::vector<BookSeries>& out, const std::vector<DeterminationInput>& dets,
                const std::string& prefix, double sigma_reading_div) {
  for (std::size_t d = 0; d < dets.size(); ++d) {
    const DeterminationInput& det = dets[d];
    const std::string base = fmt::format("{}[{}]", prefix, d);
    const auto add = [&](const std::string& member, SeriesKind kind, const std::vector<double>& readings,
                         double booked) {
      BookSeries s{base + "." + member, det.label, {}};
      s.input.kind = kind;
      s.input.readings = readings;
      s.input.booked_sigma = booked;
      out.push_back(std::move(s));
    };
    if (det.mode == Mode::Tracking && !det.tracking.reversals_rad.empty())
      add("reversals", SeriesKind::Circle, det.tracking.reversals_rad, det.tracking.sigma_reading_rad);
    if (det.zero_before) add("zero_before", SeriesKind::Scale, det.zero_before->reversals_div, sigma_reading_div);
    if (det.zero_after) add("zero_after", SeriesKind::Scale, det.zero_after->reversals_div, sigma_reading_div);
  }
}

// A book without any series long enough: how many it has and the longest, and why 6.
InputError no_series_error(const StochasticBookInput& in) {
  std::size_t longest = 0;
  for (const BookSeries& s : in.series) longest = std::max(longest, s.input.readings.size());
  return InputError(
      fmt::format("{} {} reversal-point series (tracking reversals, zero-position runs) has at "
                  "least {} readings (the longest has {}): the stochastic models need 3 unknowns "
                  "(M, A', c), 2 variance components and 1 more, and a standard programme of 5 "
                  "reversals per run is below that",
                  in.campaign ? "this is a campaign file; none of its" : "none of the", in.series.size(),
                  kMinStochasticSeries, longest),
      ErrorContext{"", std::nullopt, in.campaign ? "line.determinations" : "determinations"});
}

}  // namespace

StochasticBookInput stochastic_book(const ReduceInput& in) {
  StochasticBookInput book;
  add_series(book.series, in.determinations, "determinations", in.instrument.sigma_reading_div);
  return book;
}

StochasticBookInput stochastic_book(const CampaignInput& in) {
  StochasticBookInput book;
  book.campaign = true;
  const double sigma_div = in.instrument.sigma_reading_div;
  if (in.known_line) {
    add_series(book.series, in.known_line->before, "known_line.before", sigma_div);
    add_series(book.series, in.known_line->after, "known_line.after", sigma_div);
  }
  add_series(book.series, in.line.determinations, "line.determinations", sigma_div);
  return book;
}

StochasticBookResult process(const StochasticBookInput& in, Progress* progress) {
  StochasticBookResult out{in.file, in.campaign, {}};
  for (const BookSeries& s : in.series) {
    if (s.input.readings.size() < kMinStochasticSeries) continue;
    StochasticSeries series{s.label.empty() ? s.field : s.field + " (" + s.label + ")", {}};
    try {
      series.result = analyse_stochastic(s.input, progress);
    } catch (Error& e) {
      // The series' field, so that the error points at its line.
      if (e.context().field.empty()) e.add_context("", std::nullopt, s.field);
      throw;
    }
    out.series.push_back(std::move(series));
  }
  if (out.series.empty()) throw no_series_error(in);
  return out;
}

}  // namespace meridian::gyro
