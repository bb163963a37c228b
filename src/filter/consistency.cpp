#include "meridian/filter/consistency.hpp"

#include <cmath>

#include <fmt/format.h>

#include "meridian/adjust/statistics.hpp"
#include "meridian/core/error.hpp"

namespace meridian::filter {
namespace {

ConsistencySeries summarise(const std::vector<ConsistencyRun>& runs,
                            std::vector<double> ConsistencyRun::*member, double dof,
                            double confidence, const char* name) {
  ConsistencySeries s;
  s.dof = dof;
  const std::size_t epochs = (runs.front().*member).size();
  if (epochs == 0) return s;
  const auto r = static_cast<std::int64_t>(runs.size());
  s.average.assign(epochs, 0.0);
  double total = 0.0;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const std::vector<double>& v = runs[i].*member;
    if (v.size() != epochs)
      throw InputError(
          fmt::format("run {} has {} {} values, run 0 has {}", i, v.size(), name, epochs));
    for (std::size_t k = 0; k < epochs; ++k) {
      if (!(std::isfinite(v[k]) && v[k] >= 0.0))
        throw InputError(fmt::format("run {}: {} of epoch {} is {}", i, name, k, v[k]));
      s.average[k] += v[k];
      total += v[k];
    }
  }
  s.epoch_interval = average_interval(dof, r, confidence);
  std::size_t inside = 0;
  for (double& a : s.average) {
    a /= static_cast<double>(r);
    if (s.epoch_interval.contains(a)) ++inside;
  }
  s.fraction_inside = static_cast<double>(inside) / static_cast<double>(epochs);
  const auto samples = r * static_cast<std::int64_t>(epochs);
  s.overall_average = total / static_cast<double>(samples);
  s.overall_interval = average_interval(dof, samples, confidence);
  return s;
}

}  // namespace

ChiSquaredInterval average_interval(double dof, std::int64_t samples, double confidence) {
  if (!(confidence > 0.0 && confidence < 1.0))
    throw InputError(fmt::format("confidence must be in (0, 1), is {}", confidence));
  if (samples < 1) throw InputError("the average needs at least one sample");
  if (!(std::isfinite(dof) && dof >= 1.0))
    throw InputError(fmt::format("degrees of freedom must be finite and ≥ 1, is {}", dof));
  const double s = static_cast<double>(samples);
  const double tail = 0.5 * (1.0 - confidence);
  return {adjust::chi_squared_upper_quantile(1.0 - tail, s * dof) / s,
          adjust::chi_squared_upper_quantile(tail, s * dof) / s};
}

MonteCarloConsistency summarise_consistency(const std::vector<ConsistencyRun>& runs,
                                            double state_dof, double innovation_dof,
                                            double confidence) {
  if (runs.empty()) throw InputError("a Monte Carlo consistency check needs at least one run");
  if (!(state_dof >= 1.0 && innovation_dof >= 1.0))
    throw InputError("state and innovation dimensions must be ≥ 1");
  MonteCarloConsistency out;
  out.runs = static_cast<int>(runs.size());
  out.confidence = confidence;
  out.nees = summarise(runs, &ConsistencyRun::nees, state_dof, confidence, "NEES");
  out.nis = summarise(runs, &ConsistencyRun::nis, innovation_dof, confidence, "NIS");
  return out;
}

}  // namespace meridian::filter
