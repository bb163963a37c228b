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

#include <array>
#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

#include "meridian/dov/deflection.hpp"

namespace meridian::report {

/// The JSON summary of `result` (the options it carries: discretisation, extraction,
/// transport rate).
nlohmann::json dov_summary_to_json(const dov::Result& result);

/// A few lines of text: the model settings of result.options (σ_model, ζ, λ, r,
/// discretisation, extraction, attitude dynamics), RMS and σ figures, NIS, ε̂_U, notes and
/// warnings.
std::string dov_summary_text(const dov::Result& result);

/// The per-epoch profile, one home for its columns (the CSV of `dov process -o` and the
/// Python package's profile): time_s, lat_deg, lon_deg (the sample's geodetic position),
/// model_eta_arcsec, model_xi_arcsec, filtered_eta_arcsec, filtered_xi_arcsec,
/// filtered_sigma_eta_arcsec, filtered_sigma_xi_arcsec, smoothed_eta_arcsec,
/// smoothed_xi_arcsec, smoothed_sigma_eta_arcsec, smoothed_sigma_xi_arcsec,
/// filtered_eps_u_deg_per_h, innovation_east_arcsec, innovation_north_arcsec, nis, accepted
/// (1 or 0), and — when the line carried truth — truth_eta_arcsec, truth_xi_arcsec.
inline constexpr std::size_t kDovProfileColumns = 20;

/// The names of the profile's columns, in order (the last two only with truth).
const std::array<const char*, kDovProfileColumns>& dov_profile_columns();

/// How many of those columns an epoch has: all with truth, the first 18 without.
std::size_t dov_profile_column_count(bool truth);

/// The values of epoch `e` in the columns' units, in their order; the truth values NaN when
/// e.truth is not set.
std::array<double, kDovProfileColumns> dov_profile_values(const dov::EpochResult& e);

/// The profile CSV is dov_profile_csv_header, then one append_dov_profile_line per epoch in
/// time order: each number with 10 significant digits, positions with 10 decimals of a degree
/// (≈ 0.01 mm).
///
/// The profile's header line (with the two truth columns when `truth`), ending in a newline.
std::string dov_profile_csv_header(bool truth);

/// Append the profile line of one epoch (its truth columns when e.truth is set), with newline.
void append_dov_profile_line(std::string& out, const dov::EpochResult& e);

/// The profile CSV of a streamed line, built an epoch at a time (a dov::EpochSink): the header
/// before the first epoch, then its line. text() is what has been built and not yet written
/// out; the caller may write it and clear it as it grows.
class DovProfileCsv {
 public:
  void add(const dov::EpochResult& e);
  std::string& text() { return text_; }

 private:
  bool header_ = false;
  std::string text_;
};

}  // namespace meridian::report
