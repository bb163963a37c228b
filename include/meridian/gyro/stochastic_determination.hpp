#pragma once
/// \file stochastic_determination.hpp
/// A tracking determination's north reading under a stochastic model of its reversal readings
/// (campaign option `stochastic_model:`, gyro-stochastic spec §4): the centre M and its σ by the
/// GLS with the covariance D of the chosen model instead of the white-noise estimate.
///
/// The series is the determination's reversal readings, unwrapped across 0°/360° and taken in
/// arc-seconds relative to the first reading rounded down to a whole degree (as
/// `meridian gyro stochastic`); the comparison of analyse_stochastic (stochastic.hpp) fits the
/// models (for markov1 only white noise and Markov-1, for markov2 also Markov-2, for recommended
/// all of them) with the booked reading σ as the booked σ. The model used:
/// * markov1: markov1-ml; markov2: markov2-ml; recommended: the recommended model (white noise:
///   the determination is left as it is, used = "white");
/// * the centre: method lsq → the GLS of (R1) with the model's D (ModelFit::r1); lsq-linear →
///   the GLS of (R2) (ModelFit::north). σ(M) = sqrt(D_Ŷ(0,0)) at the estimated components (not
///   rescaled by σ̂0).
/// Then N_G = M − λ·τ·α_p (north_from_tracking) with the determination's α_p, as before.
///
/// It cannot be used — the series has fewer than 6 readings (8 for markov2), the model is not
/// fitted or is degenerate (stochastic.hpp), its (R1) GLS failed, the method is two-point or
/// schuler (no GLS), or the determination is non-tracking — then N_G stays the white-noise
/// result: with `strict` false the determination gets a warning and StochasticUse::fallback;
/// with `strict` true (a request of the determination itself) InputError at field
/// "stochastic_model".

#include "meridian/gyro/determination.hpp"
#include "meridian/gyro/instrument.hpp"
#include "meridian/gyro/stochastic_choice.hpp"

namespace meridian::gyro {

/// `reduced` (reduce_determination of `in` with `inst`) with N_G, the reversal fit's centre,
/// amplitude, damping and residuals (radians; amplitude A and decay κ of (R1) for lsq, A′ and c
/// of (R2) for lsq-linear) replaced by the GLS under `choice`, and `stochastic` filled.
/// StochasticChoice::White returns `reduced` unchanged (but for `stochastic.requested`).
/// Throws InputError (field "stochastic_model") as described above when `strict`.
DeterminationResult with_stochastic_model(DeterminationResult reduced, const DeterminationInput& in,
                                          const Instrument& inst, StochasticChoice choice,
                                          bool strict);

}  // namespace meridian::gyro
