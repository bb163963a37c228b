#include "meridian/io/gyro_stochastic.hpp"

#include <cmath>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gyro/reversal.hpp"
#include "meridian/io/document.hpp"
#include "meridian/io/gyro_files.hpp"

namespace meridian::io {

StochasticJob run_stochastic_file(const std::filesystem::path& path, Progress* progress) {
  const GyroReduceFile f = read_gyro_reduce_file(path);
  StochasticJob job;
  job.file = f.file;
  const auto& dets = f.input.determinations;
  const auto add = [&](std::string field, std::string label, bool tracking, double ref,
                       std::vector<double> readings) {
    gyro::StochasticSeries s;
    s.label = label.empty() ? field : field + " (" + label + ")";
    s.tracking = tracking;
    s.reference_rad = ref;
    s.input.readings = std::move(readings);
    try {
      s.result = gyro::analyse_stochastic(s.input, progress);
    } catch (Error& e) {
      // The series' field ("determinations[2].reversals"), so the error points at its line.
      e.add_context("", std::nullopt, e.context().field.empty() ? field : "");
      locate_error(e, f.file, f.lines);
      throw;
    }
    job.result.series.push_back(std::move(s));
  };
  for (std::size_t d = 0; d < dets.size(); ++d) {
    const auto& det = dets[d];
    const std::string base = fmt::format("determinations[{}]", d);
    if (det.mode == gyro::Mode::Tracking && det.tracking.reversals_rad.size() >= 6) {
      const auto un = gyro::unwrap_circle_readings(det.tracking.reversals_rad);
      const double ref = std::floor(un.front() / units::kDegree) * units::kDegree;
      std::vector<double> arcsec;
      for (double r : un) arcsec.push_back(units::rad_to_arcsec(r - ref));
      add(base + ".reversals", det.label, true, ref, std::move(arcsec));
    }
    if (det.zero_before && det.zero_before->reversals_div.size() >= 6)
      add(base + ".zero_before", det.label, false, 0.0, det.zero_before->reversals_div);
    if (det.zero_after && det.zero_after->reversals_div.size() >= 6)
      add(base + ".zero_after", det.label, false, 0.0, det.zero_after->reversals_div);
  }
  if (job.result.series.empty())
    throw InputError(
        "no reversal-point series with at least 6 readings (tracking reversals or "
        "zero-position runs): the stochastic models need 3 unknowns, 2 variance "
        "components and 1 more",
        ErrorContext{f.file, std::nullopt, "determinations"});
  return job;
}

}  // namespace meridian::io
