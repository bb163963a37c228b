#pragma once
/// \file dov_outputs.hpp
/// Outputs of the dynamic deflection-of-the-vertical workflow (docs/deflection.md, "Outputs"):
/// the JSON summary, a short text summary and the per-epoch profile CSV. Angles in arcseconds
/// (keys and columns carry the unit), ε_U in °/h; signs of η, ξ as geodesy/frames.hpp.
///
/// JSON summary keys: epochs, statistics_epochs, discretisations, rejected;
/// rms_arcsec {model, filtered, smoothed: {eta, xi}} (only with truth); mean_sigma_arcsec
/// {filtered, smoothed: {eta, xi}} — the quadratic mean √(mean σ²), the figure to compare with
/// an RMS error; nis {mean, lower_95, upper_95}; nees {filtered, smoothed} (only with true
/// states); eps_u_deg_per_h {value, sigma} (smoothed); discretisation, extraction; notes,
/// warnings.

#include <string>

#include <nlohmann/json.hpp>

#include "meridian/dov/deflection.hpp"

namespace meridian::report {

/// The JSON summary of `result`, computed with `options`.
nlohmann::json dov_summary_to_json(const dov::Result& result, const dov::Options& options);

/// A few lines of text: the model settings of `options` (σ_model, ζ, λ, r, discretisation,
/// extraction), RMS and σ figures, NIS, ε̂_U, notes and warnings.
std::string dov_summary_text(const dov::Result& result, const dov::Options& options);

/// The profile CSV is dov_profile_csv_header, then one append_dov_profile_line per epoch in
/// time order (`dov process` streams them into its output file): time_s, lat_deg, lon_deg
/// (the sample's geodetic position, 10 decimals of a degree ≈ 0.01 mm), model_eta_arcsec, model_xi_arcsec,
/// filtered_eta_arcsec, filtered_xi_arcsec, filtered_sigma_eta_arcsec, filtered_sigma_xi_arcsec,
/// smoothed_eta_arcsec, smoothed_xi_arcsec, smoothed_sigma_eta_arcsec, smoothed_sigma_xi_arcsec,
/// filtered_eps_u_deg_per_h, innovation_east_arcsec, innovation_north_arcsec, nis, accepted
/// (1 or 0), and — when the line carried truth — truth_eta_arcsec, truth_xi_arcsec;
/// 10 significant digits.
///
/// The profile's header line (with the two truth columns when `truth`), ending in a newline.
std::string dov_profile_csv_header(bool truth);

/// Append the profile line of one epoch (its truth columns when e.truth is set), with newline.
/// Each number with 10 significant digits, positions with 10 decimals.
void append_dov_profile_line(std::string& out, const dov::EpochResult& e);

}  // namespace meridian::report
