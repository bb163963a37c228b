#include "meridian/gyro/stochastic_determination.hpp"

#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "meridian/core/angle.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gyro/reversal.hpp"
#include "meridian/gyro/stochastic.hpp"

namespace meridian::gyro {

std::string to_string(StochasticChoice c) {
  switch (c) {
    case StochasticChoice::White:
      return "white";
    case StochasticChoice::Markov1:
      return "markov1";
    case StochasticChoice::Markov2:
      return "markov2";
    case StochasticChoice::Recommended:
      return "recommended";
  }
  return "?";
}

StochasticChoice stochastic_choice_from_string(const std::string& name) {
  for (StochasticChoice c : {StochasticChoice::White, StochasticChoice::Markov1,
                             StochasticChoice::Markov2, StochasticChoice::Recommended})
    if (to_string(c) == name) return c;
  throw InputError(fmt::format(
      "unknown stochastic model \"{}\" (expected white, markov1, markov2 or recommended)", name));
}

namespace {

// The GLS under the chosen model of the functional model of the determination's method ((R1)
// for lsq, (R2) for lsq-linear): centre, amplitude and decay (κ of (R1), c of (R2)).
struct GlsCentre {
  Uncertain centre, amplitude, decay;  // arcsec relative to the series' reference; κ or c
  Eigen::VectorXd residuals;           // arcsec
};

}  // namespace

DeterminationResult with_stochastic_model(DeterminationResult reduced, const DeterminationInput& in,
                                          const Instrument& inst, StochasticChoice choice,
                                          bool strict) {
  DeterminationResult r = std::move(reduced);
  r.stochastic = StochasticUse{};
  r.stochastic.requested = choice;
  if (choice == StochasticChoice::White) return r;

  // The requested model cannot be used: an error for a determination's own request, else white
  // noise with a warning.
  const auto cannot = [&](const std::string& why) -> DeterminationResult {
    const std::string msg =
        fmt::format("stochastic_model {} cannot be used: {}", to_string(choice), why);
    if (strict) throw InputError(msg, ErrorContext{"", std::nullopt, "stochastic_model"});
    r.stochastic.fallback = true;
    r.stochastic.reason = why;
    r.warnings.push_back(msg + "; white noise used");
    return std::move(r);
  };

  if (r.mode != Mode::Tracking || !r.primary.reversal)
    return cannot("it applies to the reversal readings of tracking determinations, this one is " +
                  to_string(r.mode));
  const auto* method = std::get_if<ReversalMethod>(&r.primary.method);
  if (!method || (*method != ReversalMethod::NonlinearLsq && *method != ReversalMethod::LinearLsq))
    return cannot(fmt::format(
        "method {} has no generalised least squares (use lsq or lsq-linear)",
        to_string(r.primary.method)));

  // The series as `gyro stochastic` takes it: arcsec relative to the first reading rounded down
  // to a whole degree.
  const std::vector<double> un = unwrap_circle_readings(in.tracking.reversals_rad);
  const std::size_t min_readings = choice == StochasticChoice::Markov2 ? 8 : 6;
  if (un.size() < min_readings)
    return cannot(fmt::format(
        "the run has {} reversal readings, the {} model needs at least {} (3 unknowns, the "
        "covariance parameters and 1 more)",
        un.size(), to_string(choice), min_readings));
  const double ref = std::floor(un.front() / units::kDegree) * units::kDegree;
  StochasticInput si;
  for (double x : un) si.readings.push_back(units::rad_to_arcsec(x - ref));
  si.booked_sigma = units::rad_to_arcsec(in.tracking.sigma_reading_rad);
  si.unit = "arcsec";
  si.options.covariance_functions = choice == StochasticChoice::Recommended;
  si.options.markov2 = choice != StochasticChoice::Markov1;
  StochasticResult res;
  try {
    res = analyse_stochastic(si);
  } catch (const Error& e) {
    return cannot(e.message());
  }
  const ModelFit* fit = nullptr;
  if (choice == StochasticChoice::Recommended) {
    fit = &res.models[static_cast<std::size_t>(res.recommended)];
    if (fit->model == StochasticModel::WhiteNoise) {
      r.stochastic.reason = "the comparison recommends white noise";
      return r;
    }
  } else {
    const StochasticModel want =
        choice == StochasticChoice::Markov1 ? StochasticModel::Markov1Ml : StochasticModel::Markov2Ml;
    for (const auto& f : res.models)
      if (f.model == want) fit = &f;
    if (!fit) {
      std::string why = fmt::format("{} was not fitted", to_string(want));
      for (const auto& n : res.notes)
        if (n.rfind(to_string(want), 0) == 0) why += " (" + n + ")";
      return cannot(why);
    }
    if (fit->degenerate)
      return cannot(fmt::format("{} is degenerate: {}", to_string(fit->model), fit->degenerate_reason));
  }

  GlsCentre g;
  const bool r1 = *method == ReversalMethod::NonlinearLsq;
  if (r1) {
    if (!fit->r1) {
      std::string why = fmt::format("the GLS of (R1) under {} failed", to_string(fit->model));
      for (const auto& n : fit->notes)
        if (n.rfind("(R1) GLS", 0) == 0) why += " (" + n + ")";
      return cannot(why);
    }
    g.centre = fit->r1->centre;
    g.amplitude = fit->r1->amplitude;
    g.decay = fit->r1->decay;
    g.residuals = fit->r1->residuals;
  } else {
    g.centre = fit->north;
    g.amplitude = fit->amplitude;
    g.decay = fit->damping;
    const Eigen::MatrixXd G = reversal_design(static_cast<int>(si.readings.size()));
    g.residuals = G * Eigen::Vector3d(fit->north.value, fit->amplitude.value, fit->damping.value) -
                  Eigen::Map<const Eigen::VectorXd>(si.readings.data(),
                                                    static_cast<Eigen::Index>(si.readings.size()));
  }

  const Uncertain centre_rad{wrap_positive_rad(ref + units::arcsec_to_rad(g.centre.value)),
                             units::arcsec_to_rad(g.centre.sigma)};
  r.stochastic.used = to_string(fit->model);
  r.stochastic.rho = fit->rho;
  r.stochastic.sigma1_arcsec = fit->sigma1.value;
  r.stochastic.sigma2_arcsec = fit->sigma2.value;
  const std::string note = fmt::format(
      "centre and sigma by generalised least squares of {} under {}{}{} (sigma1 = {:.3g}\"{})",
      r1 ? "(R1)" : "(R2)", to_string(fit->model),
      fit->rho.empty() ? "" : fmt::format(", rho = {:.3f}", fmt::join(fit->rho, ", ")),
      fit->shape.empty() ? "" : fmt::format(", shape {:.3g}", fmt::join(fit->shape, ", ")),
      fit->sigma1.value,
      std::isfinite(fit->sigma2.value) ? fmt::format(", sigma2 = {:.3g}\"", fit->sigma2.value) : "");
  // The white-noise warning "… the larger, a-posteriori sigma is used" no longer says what
  // gives σ(N_G): say so.
  if (const std::string w = reading_sigma_warning(*r.primary.reversal, units::kArcsecond, "\"", 1);
      !w.empty())
    for (auto& x : r.warnings)
      if (x.size() >= w.size() && x.compare(x.size() - w.size(), w.size(), w) == 0)
        x += fmt::format(" for white noise; N_G and its sigma are from the GLS under {} instead",
                         to_string(fit->model));
  const auto update = [&](MethodResult& m) {
    ReversalResult& rv = *m.reversal;
    rv.centre = centre_rad;
    rv.amplitude = Uncertain{units::arcsec_to_rad(g.amplitude.value),
                             units::arcsec_to_rad(g.amplitude.sigma)};
    // κ is dimensionless; c of (R2) is an angle.
    rv.damping = r1 ? g.decay
                    : Uncertain{units::arcsec_to_rad(g.decay.value),
                                units::arcsec_to_rad(g.decay.sigma)};
    rv.residuals.clear();
    for (Eigen::Index i = 0; i < g.residuals.size(); ++i)
      rv.residuals.push_back(units::arcsec_to_rad(g.residuals(i)));
    rv.sigma_is_aposteriori = false;
    rv.sigma_from_gls = true;
    rv.notes.push_back(note);
    m.north = north_from_tracking(centre_rad, inst, r.zero_position_used);
  };
  update(r.primary);
  for (auto& m : r.all)
    if (m.method == r.primary.method && m.reversal) update(m);
  return r;
}

}  // namespace meridian::gyro
