#include "meridian/gyro/regulations.hpp"

#include <cmath>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"

namespace meridian::gyro {
namespace {

struct ClassRow {
  double class_arcsec;
  double runs, constants, means, orientations, mean_sigma;  // arcsec
};

// gyro/regulations.hpp documents the table and its sources.
constexpr ClassRow kRows[] = {
    {5.0, 10.0, 10.0, 15.0, 15.0, 4.0},
    {15.0, 40.0, 40.0, 40.0, 40.0, 10.0},
    {25.0, 70.0, 70.0, 70.0, 60.0, 15.0},
};

}  // namespace

RegulationLimits regulation_limits(double accuracy_class_arcsec) {
  if (!std::isfinite(accuracy_class_arcsec) || accuracy_class_arcsec <= 0.0)
    throw InputError(fmt::format("accuracy class {}\" must be a positive number of arc-seconds", accuracy_class_arcsec),
                     {"", std::nullopt, "instrument.accuracy_class_arcsec"});
  const ClassRow* row = &kRows[2];
  double scale = 1.0;
  for (const ClassRow& r : kRows)
    if (accuracy_class_arcsec <= r.class_arcsec) {
      row = &r;
      break;
    }
  if (accuracy_class_arcsec > kRows[2].class_arcsec) scale = accuracy_class_arcsec / kRows[2].class_arcsec;
  RegulationLimits l;
  l.accuracy_class_arcsec = accuracy_class_arcsec;
  l.run_difference_rad = scale * row->runs * units::kArcsecond;
  l.constant_difference_rad = scale * row->constants * units::kArcsecond;
  l.constant_means_rad = scale * row->means * units::kArcsecond;
  l.orientation_difference_rad = scale * row->orientations * units::kArcsecond;
  l.orientation_mean_sigma_rad = scale * row->mean_sigma * units::kArcsecond;
  l.instrument_constant_max_rad = 600.0 * units::kArcsecond;
  l.default_reading_sigma_rad = accuracy_class_arcsec / 3.0 * units::kArcsecond;
  if (row->class_arcsec == 5.0)
    l.source = fmt::format("project limits for a {}\"-class instrument (gyro total station; spec 7.1)",
                           accuracy_class_arcsec);
  else if (scale > 1.0)
    l.source = fmt::format("coal-mine surveying regulations, 25\"-class limits scaled to the {}\" class",
                           accuracy_class_arcsec);
  else
    l.source = fmt::format("coal-mine surveying regulations, {}\"-class instrument", row->class_arcsec);
  return l;
}

RegulationLimits apply_tolerances(RegulationLimits l, const Tolerances& t) {
  auto set = [](const std::optional<double>& v, double& target) {
    if (v) target = *v;
  };
  set(t.determination_difference_rad, l.run_difference_rad);
  set(t.instrument_constant_difference_rad, l.constant_difference_rad);
  if (t.instrument_constant_difference_rad && !t.instrument_constant_means_rad)
    l.constant_means_rad = *t.instrument_constant_difference_rad;
  set(t.instrument_constant_means_rad, l.constant_means_rad);
  set(t.orientation_difference_rad, l.orientation_difference_rad);
  set(t.orientation_mean_sigma_rad, l.orientation_mean_sigma_rad);
  set(t.zero_position_div, l.zero_position_drift_div);
  set(t.zero_position_limit_div, l.zero_position_div);
  set(t.instrument_constant_max_rad, l.instrument_constant_max_rad);
  return l;
}

}  // namespace meridian::gyro
