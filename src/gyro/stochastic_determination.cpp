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

// Why the requested model cannot be used (empty: it can), or what it gives.
template <class T>
struct Usable {
  std::optional<T> value;
  std::string why;
};

// The requested model cannot be used: an error for a determination's own request (`strict`),
// else white noise with a warning.
DeterminationResult cannot_use(DeterminationResult r, StochasticChoice choice, bool strict,
                               const std::string& why) {
  const std::string msg = fmt::format("stochastic_model {} cannot be used: {}", to_string(choice), why);
  if (strict) throw InputError(msg, ErrorContext{"", std::nullopt, "stochastic_model"});
  r.stochastic.fallback = true;
  r.stochastic.reason = why;
  r.warnings.push_back(msg + "; white noise used");
  return r;
}

// A tracking determination whose method has a GLS (lsq, lsq-linear); else why not.
Usable<ReversalMethod> gls_method(const DeterminationResult& r) {
  if (r.mode != Mode::Tracking || !r.primary.reversal)
    return {std::nullopt, "it applies to the reversal readings of tracking determinations, this one is " +
                              to_string(r.mode)};
  const auto* method = std::get_if<ReversalMethod>(&r.primary.method);
  if (!method || (*method != ReversalMethod::NonlinearLsq && *method != ReversalMethod::LinearLsq))
    return {std::nullopt, fmt::format("method {} has no generalised least squares (use lsq or lsq-linear)",
                                      to_string(r.primary.method))};
  return {*method, {}};
}

// The comparison of analyse_stochastic on the run's reversal readings, with only the models the
// choice needs; else why not.
Usable<StochasticResult> compare_models(const DeterminationInput& in, StochasticChoice choice) {
  const std::size_t n = in.tracking.reversals_rad.size();
  const std::size_t min_readings = choice == StochasticChoice::Markov2 ? 8 : 6;
  if (n < min_readings)
    return {std::nullopt,
            fmt::format("the run has {} reversal readings, the {} model needs at least {} (3 unknowns, the "
                        "covariance parameters and 1 more)",
                        n, to_string(choice), min_readings)};
  StochasticInput si;
  si.kind = SeriesKind::Circle;
  si.readings = in.tracking.reversals_rad;
  si.booked_sigma = in.tracking.sigma_reading_rad;
  si.options.covariance_functions = choice == StochasticChoice::Recommended;
  si.options.markov2 = choice != StochasticChoice::Markov1;
  try {
    return {analyse_stochastic(si), {}};
  } catch (const Error& e) {
    return {std::nullopt, e.message()};
  }
}

// The fit of the requested Markov model (markov1 → markov1-ml, markov2 → markov2-ml), or the
// recommended one; else why not.
Usable<const ModelFit*> chosen_fit(const StochasticResult& res, StochasticChoice choice) {
  if (choice == StochasticChoice::Recommended)
    return {&res.models[static_cast<std::size_t>(res.recommended)], {}};
  const StochasticModel want =
      choice == StochasticChoice::Markov1 ? StochasticModel::Markov1Ml : StochasticModel::Markov2Ml;
  const ModelFit* fit = nullptr;
  for (const auto& f : res.models)
    if (f.model == want) fit = &f;
  if (!fit) {
    std::string why = fmt::format("{} was not fitted", to_string(want));
    for (const auto& n : res.notes)
      if (n.rfind(to_string(want), 0) == 0) why += " (" + n + ")";
    return {std::nullopt, why};
  }
  if (fit->degenerate)
    return {std::nullopt, fmt::format("{} is degenerate: {}", to_string(fit->model), fit->degenerate_reason)};
  return {fit, {}};
}

// The centre of (R1) (method lsq) or (R2) (lsq-linear) under the fit's covariance; else why not.
Usable<GlsCentre> gls_centre(const ModelFit& fit, const StochasticResult& res, bool r1) {
  GlsCentre g;
  if (r1) {
    if (!fit.r1) {
      std::string why = fmt::format("the GLS of (R1) under {} failed", to_string(fit.model));
      for (const auto& n : fit.notes)
        if (n.rfind("(R1) GLS", 0) == 0) why += " (" + n + ")";
      return {std::nullopt, why};
    }
    g.centre = fit.r1->centre;
    g.amplitude = fit.r1->amplitude;
    g.decay = fit.r1->decay;
    g.residuals = fit.r1->residuals;
    return {g, {}};
  }
  g.centre = fit.north;
  g.amplitude = fit.amplitude;
  g.decay = fit.damping;
  const std::vector<double>& l = res.fitted_readings;
  const Eigen::MatrixXd G = reversal_design(static_cast<int>(l.size()));
  g.residuals = G * Eigen::Vector3d(fit.north.value, fit.amplitude.value, fit.damping.value) -
                Eigen::Map<const Eigen::VectorXd>(l.data(), static_cast<Eigen::Index>(l.size()));
  return {g, {}};
}

// The note of every reversal result the GLS replaced.
std::string gls_note(const ModelFit& fit, bool r1) {
  return fmt::format(
      "centre and sigma by generalised least squares of {} under {}{}{} (sigma1 = {:.3g}\"{})",
      r1 ? "(R1)" : "(R2)", to_string(fit.model),
      fit.rho.empty() ? "" : fmt::format(", rho = {:.3f}", fmt::join(fit.rho, ", ")),
      fit.shape.empty() ? "" : fmt::format(", shape {:.3g}", fmt::join(fit.shape, ", ")),
      fit.sigma1.value,
      std::isfinite(fit.sigma2.value) ? fmt::format(", sigma2 = {:.3g}\"", fit.sigma2.value) : "");
}

// `r` with N_G, the reversal fit's centre, amplitude, damping and residuals of the primary method
// (and of the same method among all) replaced by the GLS `g` of `fit` (arcsec relative to `ref_rad`).
void apply_gls(DeterminationResult& r, const Instrument& inst, const ModelFit& fit, const GlsCentre& g,
               double ref_rad, bool r1) {
  const Uncertain centre_rad{wrap_positive_rad(ref_rad + units::arcsec_to_rad(g.centre.value)),
                             units::arcsec_to_rad(g.centre.sigma)};
  r.stochastic.used = to_string(fit.model);
  r.stochastic.rho = fit.rho;
  r.stochastic.sigma1_arcsec = fit.sigma1.value;
  r.stochastic.sigma2_arcsec = fit.sigma2.value;
  const std::string note = gls_note(fit, r1);
  // The white-noise warning "… the larger, a-posteriori sigma is used" no longer says what
  // gives σ(N_G): say so.
  if (const std::string w = reading_sigma_warning(*r.primary.reversal, units::kArcsecond, "\"", 1);
      !w.empty())
    for (auto& x : r.warnings)
      if (x.size() >= w.size() && x.compare(x.size() - w.size(), w.size(), w) == 0)
        x += fmt::format(" for white noise; N_G and its sigma are from the GLS under {} instead",
                         to_string(fit.model));
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
}

}  // namespace

DeterminationResult with_stochastic_model(DeterminationResult reduced, const DeterminationInput& in,
                                          const Instrument& inst, StochasticChoice choice,
                                          bool strict) {
  DeterminationResult r = std::move(reduced);
  r.stochastic = StochasticUse{};
  r.stochastic.requested = choice;
  if (choice == StochasticChoice::White) return r;
  const Usable<ReversalMethod> method = gls_method(r);
  if (!method.value) return cannot_use(std::move(r), choice, strict, method.why);
  const Usable<StochasticResult> res = compare_models(in, choice);
  if (!res.value) return cannot_use(std::move(r), choice, strict, res.why);
  const Usable<const ModelFit*> fit = chosen_fit(*res.value, choice);
  if (!fit.value) return cannot_use(std::move(r), choice, strict, fit.why);
  if (choice == StochasticChoice::Recommended && (*fit.value)->model == StochasticModel::WhiteNoise) {
    r.stochastic.reason = "the comparison recommends white noise";
    return r;
  }
  const bool r1 = *method.value == ReversalMethod::NonlinearLsq;
  const Usable<GlsCentre> g = gls_centre(**fit.value, *res.value, r1);
  if (!g.value) return cannot_use(std::move(r), choice, strict, g.why);
  apply_gls(r, inst, **fit.value, *g.value, res.value->reference_rad, r1);
  return r;
}

}  // namespace meridian::gyro
