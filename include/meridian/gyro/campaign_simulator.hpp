#pragma once
/// \file campaign_simulator.hpp
/// Simulate a whole station campaign from a known truth: the true grid
/// azimuths of the known line and of the unknown line follow from the
/// points' grid coordinates; the chain of spec §6 is run backwards
/// (T → α → A → A_G → N_G) and every determination's observations are
/// simulated with the reversal/oscillation simulators. Used for planning,
/// for the bundled example and for end-to-end validation.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "meridian/gyro/campaign.hpp"

namespace meridian::gyro {

struct CampaignTruth {
  std::string name = "simulated campaign";
  InstrumentSpec instrument;               ///< τ, λ (at constants_latitude), σ settings
  /// T_B at the latitude where λ was determined (s); rescaled to each station
  /// by T_B² ∝ 1/(cos φ·(1+λ(φ))).
  double nontracking_period_s = 440.0;
  geodesy::GridDefinition grid;
  PointInput station, target;              ///< the unknown line C→D (grid coordinates)
  PointInput known_station, known_target;  ///< the known line A→B (grid coordinates)
  double eta_station_rad = 0.0;            ///< true η at C (used to simulate)
  double eta_known_rad = 0.0;              ///< true η at A
  /// True ξ at C and at A. When given, the truth uses the full Laplace
  /// equation, with the zenith distance of each line's sight from the
  /// heights of its points (geodesy/sight.hpp; horizontal when a height is
  /// missing), and give_eta writes ξ too. None: the truth neglects the
  /// zenith-distance term (α = A − η·tan φ), as before it existed.
  std::optional<double> xi_station_rad, xi_known_rad;
  bool give_eta = true;                    ///< write η (and ξ when known) into the campaign input
  double instrument_constant_rad = 0.0;    ///< true E
  double alpha_p_div = 0.3;                ///< true tape zero position
  double alpha_p_drift_div = 0.05;         ///< change of α_p from before to after each run
  int known_before = 2, known_after = 2;   ///< determinations on the known line
  int line_nontracking = 2;                ///< non-tracking determinations on the line
  int line_tracking = 1;                   ///< tracking determinations on the line
  double amplitude_div = 9.0;              ///< B of the non-tracking oscillations
  double max_clamp_offset_arcmin = 6.0;    ///< |N_G − N′| drawn up to this
  double sigma_time_s = kDefaultSigmaTime_s;               ///< white timing noise (0 = noise-free)
  double sigma_reading_div = kDefaultSigmaReading_div;         ///< white reading noise (0 = noise-free)
  double sigma_tracking_arcsec = 8.0;      ///< tracking reversal reading noise
  double sigma_pointing_arcsec = 2.0;      ///< target pointing noise
  double known_azimuth_sigma_arcsec = 3.0; ///< σ stated for the known azimuth
  /// Round observations to field-book precision (times 1 ms, scale
  /// readings 0.01 div, circle readings 0.1″); off for exact validation.
  bool round_to_field_precision = true;
};

/// The campaign input a field crew would bring back, and the truth values
/// the processing should recover.
struct SimulatedCampaign {
  CampaignInput input;
  double true_grid_azimuth_rad = 0.0;      ///< T of the chord C→D
  double true_known_grid_azimuth_rad = 0.0;
  std::vector<std::string> truth;          ///< the truth in words, one line each (for the file header)
};

/// Deterministic for a given seed. Throws InputError for unusable truths
/// (missing grid coordinates, latitude beyond the limit, …).
SimulatedCampaign simulate_campaign(const CampaignTruth& truth, std::uint64_t seed);

/// The truth behind the bundled example (examples/campaign.yaml): a mine
/// shaft station in Shanxi on the CGCS2000 Gauss–Krüger 3° zone 38.
CampaignTruth example_campaign_truth();

}  // namespace meridian::gyro
