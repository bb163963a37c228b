#pragma once
/// \file gyro_stochastic.hpp
/// Text and JSON of `meridian gyro stochastic` (gyro/stochastic_book.hpp): per series the
/// model-comparison table, the likelihood-ratio tests and the recommended model.
///
/// The writers take only the result: the book's name, each series' kind, reference reading and
/// booked σ are in it (gyro::StochasticBookResult, gyro::StochasticResult).
///
/// JSON: {file, series: [{label, kind ("tracking" | "zero-position"), readings, models: [...],
/// recommended, tests: [...], notes, warnings, booked_sigma_reading_arcsec |
/// booked_sigma_reading_div, r2_misfit_rms_arcsec | r2_misfit_rms_div}]}. Each model: name,
/// north_reading_deg and north_reading_dms (tracking; the centre reference + M normalised to
/// [0, 360)) or zero_position_div (zero-position runs),
/// sigma_north_arcsec | sigma_zero_position_div, amplitude_arcsec | amplitude_div (A′ of
/// (R2), signed), sigma_amplitude_*, rho [..], rho_sigma [..], sigma1_*, sigma1_sigma_*,
/// sigma2_*, sigma2_sigma_*, signal_influence_* (ΔM), signal_influence_amplitude_*,
/// log_likelihood (REML), aic, bic, covariance_parameters, vce_iterations, recommended
/// (true for exactly one), r1 (the GLS of (R1) with the model's D: north_reading_deg,
/// north_reading_dms, sigma_north_arcsec | zero_position_div, sigma_zero_position_div,
/// amplitude_*, sigma_amplitude_*, decay_per_half_period, sigma_decay_per_half_period,
/// iterations; null when not computed, the reason in notes), notes. Values that do not apply
/// or cannot be stated are null.

#include <string>

#include <nlohmann/json.hpp>

#include "meridian/gyro/stochastic_book.hpp"
#include "meridian/report/html.hpp"

namespace meridian::report {

/// JSON of the analysis of a field book.
nlohmann::json stochastic_to_json(const gyro::StochasticBookResult& book);

/// The comparison table per series (fixed-width text; σ in arcsec or div).
std::string stochastic_text(const gyro::StochasticBookResult& book);

/// `--report FILE.html`: per series a section (id "series-<i>", i from 1) with the
/// model-comparison table, the warnings and notes, the likelihood-ratio tests, the residual
/// autocorrelation of the OLS fit with each model's implied autocorrelation (lags 0 … n/2), and
/// the profile REML of Markov-2 over the (ρ_1, ρ_2) grid (when fitted).
Document stochastic_document(const gyro::StochasticBookResult& book);

}  // namespace meridian::report
