#include "meridian/io/gyro_stochastic.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gyro/reversal.hpp"
#include "meridian/io/document.hpp"
#include "meridian/io/gyro_files.hpp"

namespace meridian::io {

namespace {

constexpr std::size_t kMinSeries = 6;

// Every series of the determinations `dets` (field prefix `prefix`, e.g. "determinations" or
// "line.determinations"), analysed and appended to job.
struct SeriesCollector {
  StochasticJob& job;
  const std::string& file;
  const FieldLines& lines;
  Progress* progress;
  double sigma_reading_div;  // the instrument's a-priori σ of a scale reading
  std::size_t seen = 0;      // series of any length
  std::size_t longest = 0;

  void add(const std::string& field, const std::string& label, bool tracking, double ref,
           std::vector<double> readings, double booked) {
    ++seen;
    longest = std::max(longest, readings.size());
    if (readings.size() < kMinSeries) return;
    gyro::StochasticSeries s;
    s.label = label.empty() ? field : field + " (" + label + ")";
    s.tracking = tracking;
    s.reference_rad = ref;
    s.input.readings = std::move(readings);
    s.input.booked_sigma = booked;
    s.input.unit = tracking ? "arcsec" : "div";
    try {
      s.result = gyro::analyse_stochastic(s.input, progress);
    } catch (Error& e) {
      // The series' field ("determinations[2].reversals"), so the error points at its line.
      e.add_context("", std::nullopt, e.context().field.empty() ? field : "");
      locate_error(e, file, lines);
      throw;
    }
    job.result.series.push_back(std::move(s));
  }

  void determinations(const std::vector<gyro::DeterminationInput>& dets, const std::string& prefix) {
    for (std::size_t d = 0; d < dets.size(); ++d) {
      const auto& det = dets[d];
      const std::string base = fmt::format("{}[{}]", prefix, d);
      if (det.mode == gyro::Mode::Tracking && !det.tracking.reversals_rad.empty()) {
        const auto un = gyro::unwrap_circle_readings(det.tracking.reversals_rad);
        const double ref = std::floor(un.front() / units::kDegree) * units::kDegree;
        std::vector<double> arcsec;
        for (double r : un) arcsec.push_back(units::rad_to_arcsec(r - ref));
        const double booked = units::rad_to_arcsec(det.tracking.sigma_reading_rad);
        add(base + ".reversals", det.label, true, ref, std::move(arcsec), booked);
      }
      if (det.zero_before)
        add(base + ".zero_before", det.label, false, 0.0, det.zero_before->reversals_div,
            sigma_reading_div);
      if (det.zero_after)
        add(base + ".zero_after", det.label, false, 0.0, det.zero_after->reversals_div,
            sigma_reading_div);
    }
  }
};

// A book without any series long enough: how many it has and the longest, and why 6.
InputError no_series_error(const std::string& lead, const SeriesCollector& c,
                           const std::string& file, const std::string& field) {
  return InputError(
      fmt::format("{} {} reversal-point series (tracking reversals, zero-position runs) has at "
                  "least {} readings (the longest has {}): the stochastic models need 3 unknowns "
                  "(M, A', c), 2 variance components and 1 more, and a standard programme of 5 "
                  "reversals per run is below that",
                  lead, c.seen, kMinSeries, c.longest),
      ErrorContext{file, std::nullopt, field});
}

}  // namespace

StochasticJob run_stochastic_file(const std::filesystem::path& path, Progress* progress) {
  StochasticJob job;
  job.file = path.string();
  // A campaign file (top-level `campaign:`) holds its determinations in known_line.before,
  // known_line.after and line.determinations; a reduce file in determinations.
  const bool campaign = Node::load_file(path).has("campaign");
  if (campaign) {
    const CampaignFile f = read_campaign_file(path);
    job.file = f.file;
    job.campaign = true;
    SeriesCollector c{job, f.file, f.lines, progress, f.campaign.instrument.sigma_reading_div};
    if (f.campaign.known_line) {
      c.determinations(f.campaign.known_line->before, "known_line.before");
      c.determinations(f.campaign.known_line->after, "known_line.after");
    }
    c.determinations(f.campaign.line.determinations, "line.determinations");
    if (job.result.series.empty())
      throw no_series_error("this is a campaign file; none of its", c, f.file, "line.determinations");
    return job;
  }
  const GyroReduceFile f = read_gyro_reduce_file(path);
  job.file = f.file;
  SeriesCollector c{job, f.file, f.lines, progress, f.input.instrument.sigma_reading_div};
  c.determinations(f.input.determinations, "determinations");
  if (job.result.series.empty())
    throw no_series_error("none of the", c, f.file, "determinations");
  return job;
}

}  // namespace meridian::io
